#pragma once
// A linked compute-shader program, compiled from a shader under shaders/ (with its #includes).

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::gl {

// Its uniforms are set by name (Program::set_uniform), as a drawing program's are.
class ComputeProgram : public Program {
 public:
  // Compiles and links shader `name` (e.g. "test/smoke.comp") from `library`. Throws GlError
  // naming the shader, with the driver's log mapped to file names, when either step fails.
  explicit ComputeProgram(std::string_view name, const ShaderLibrary& library = ShaderLibrary());

  // use(), then glDispatchCompute. Throws GlError when a count exceeds the device's limit.
  void dispatch(std::uint32_t groups_x, std::uint32_t groups_y = 1,
                std::uint32_t groups_z = 1) const;
  // Enough work groups along x for `invocations` threads; the shader must skip the indices
  // past the end of its data, since the last group may reach beyond it.
  void dispatch_covering(std::uint32_t invocations) const;
  // use(), then glDispatchComputeIndirect with the work-group counts at uint `word` of buffer
  // `args` (a GL buffer name), which earlier shaders wrote: call command_barrier() after them.
  void dispatch_indirect(std::uint32_t args, std::uint32_t word) const;

  // The layout(local_size_x/y/z) of the shader.
  [[nodiscard]] const std::array<std::uint32_t, 3>& work_group_size() const noexcept {
    return work_group_size_;
  }
  [[nodiscard]] const std::string& shader_name() const noexcept { return shader_name_; }

 private:
  std::string shader_name_;
  std::array<std::uint32_t, 3> work_group_size_{};
  std::array<std::uint32_t, 3> max_work_group_count_{};
};

// Makes shader-storage writes of earlier dispatches visible to later ones: call between
// dispatches where one reads what another wrote.
void storage_barrier();

// Makes shader-storage writes of earlier dispatches visible to later ones and to the indirect
// dispatches reading their arguments from them.
void command_barrier();

// glMemoryBarrier with any GL_*_BARRIER_BIT combination.
void memory_barrier(std::uint32_t barrier_bits);

}  // namespace deformcd::gl
