#pragma once
// A linked vertex + fragment program built from shaders under shaders/ (with their #includes),
// the drawing counterpart of gl::ComputeProgram: the same gl::Program, the same error reporting.

#include <string>
#include <string_view>

#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::render {

// Its uniforms are set by name (gl::Program::set_uniform).
class GraphicsProgram : public gl::Program {
 public:
  // Compiles `vertex` and `fragment` (e.g. "render/surface.vert") from `library` and links
  // them. Throws GlError naming the shader, with the driver's log mapped to file names and
  // lines, when a step fails.
  GraphicsProgram(std::string_view vertex, std::string_view fragment,
                  const gl::ShaderLibrary& library);

  // "VERTEX + FRAGMENT", for messages.
  [[nodiscard]] const std::string& shader_names() const noexcept { return names_; }

 private:
  std::string names_;
};

}  // namespace deformcd::render
