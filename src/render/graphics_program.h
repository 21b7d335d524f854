#pragma once
// A linked vertex + fragment program built from shaders under shaders/ (with their #includes),
// the drawing counterpart of gl::ComputeProgram, with the same error reporting.

#include <cstdint>
#include <string>
#include <string_view>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::render {

class GraphicsProgram {
 public:
  // Compiles `vertex` and `fragment` (e.g. "render/surface.vert") from `library` and links
  // them. Throws GlError naming the shader, with the driver's log mapped to file names and
  // lines, when a step fails.
  GraphicsProgram(std::string_view vertex, std::string_view fragment,
                  const gl::ShaderLibrary& library);
  ~GraphicsProgram();
  GraphicsProgram(const GraphicsProgram&) = delete;
  GraphicsProgram& operator=(const GraphicsProgram&) = delete;

  void use() const;

  // Uniform setters (glProgramUniform*, no use() needed). Throw GlError when the program has
  // no active uniform `name`: it is misspelt, or unused so that the compiler removed it.
  void set_uniform(std::string_view name, std::int32_t value);
  void set_uniform(std::string_view name, std::uint32_t value);
  void set_uniform(std::string_view name, float value);
  void set_uniform(std::string_view name, const glm::vec3& value);
  void set_uniform(std::string_view name, const glm::vec4& value);
  void set_uniform(std::string_view name, const glm::mat4& value);

  [[nodiscard]] std::uint32_t name() const noexcept { return program_; }
  // "VERTEX + FRAGMENT", for messages.
  [[nodiscard]] const std::string& shader_names() const noexcept { return names_; }

 private:
  std::uint32_t program_ = 0;
  std::string names_;
  gl::ProgramUniforms uniforms_{0, {}};
};

}  // namespace deformcd::render
