#pragma once
// A linked compute-shader program, compiled from a shader under shaders/ (with its #includes).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::gl {

class ComputeProgram {
 public:
  // Compiles and links shader `name` (e.g. "test/smoke.comp") from `library`. Throws GlError
  // naming the shader, with the driver's log mapped to file names, when either step fails.
  explicit ComputeProgram(std::string_view name, const ShaderLibrary& library = ShaderLibrary());
  ~ComputeProgram();
  ComputeProgram(ComputeProgram&& other) noexcept;
  ComputeProgram& operator=(ComputeProgram&& other) noexcept;
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  void use() const;
  // use(), then glDispatchCompute. Throws GlError when a count exceeds the device's limit.
  void dispatch(std::uint32_t groups_x, std::uint32_t groups_y = 1,
                std::uint32_t groups_z = 1) const;
  // Enough work groups along x for `invocations` threads; the shader must skip the indices
  // past the end of its data, since the last group may reach beyond it.
  void dispatch_covering(std::uint32_t invocations) const;

  // Uniform setters (glProgramUniform*, no use() needed). Throw GlError when the program has
  // no active uniform `name`: it is misspelt, or unused so that the compiler removed it.
  void set_uniform(std::string_view name, std::uint32_t value);
  void set_uniform(std::string_view name, std::int32_t value);
  void set_uniform(std::string_view name, float value);
  void set_uniform(std::string_view name, const glm::vec3& value);
  void set_uniform(std::string_view name, const glm::vec4& value);

  // The layout(local_size_x/y/z) of the shader.
  [[nodiscard]] const std::array<std::uint32_t, 3>& work_group_size() const noexcept {
    return work_group_size_;
  }
  [[nodiscard]] std::uint32_t name() const noexcept { return program_; }
  [[nodiscard]] const std::string& shader_name() const noexcept { return shader_name_; }

 private:
  std::uint32_t program_ = 0;
  std::string shader_name_;
  std::array<std::uint32_t, 3> work_group_size_{};
  std::array<std::uint32_t, 3> max_work_group_count_{};
  ProgramUniforms uniforms_{0, {}};
};

// Makes shader-storage writes of earlier dispatches visible to later ones: call between
// dispatches where one reads what another wrote.
void storage_barrier();

// glMemoryBarrier with any GL_*_BARRIER_BIT combination.
void memory_barrier(std::uint32_t barrier_bits);

}  // namespace deformcd::gl
