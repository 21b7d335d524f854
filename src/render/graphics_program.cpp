#include "render/graphics_program.h"

#include <epoxy/gl.h>

#include <string>

namespace deformcd::render {

namespace {

std::string joined(std::string_view vertex, std::string_view fragment) {
  return std::string(vertex) + " + " + std::string(fragment);
}

}  // namespace

GraphicsProgram::GraphicsProgram(std::string_view vertex, std::string_view fragment,
                                 const gl::ShaderLibrary& library)
    : gl::Program({{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, library,
                  "shaders '" + joined(vertex, fragment) + "'",
                  "shaders '" + joined(vertex, fragment) + "' have"),
      names_(joined(vertex, fragment)) {}

}  // namespace deformcd::render
