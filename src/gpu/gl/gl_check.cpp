#include "gpu/gl/gl_check.h"

#include <epoxy/gl.h>

#include <sstream>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/gl_debug_log.h"

namespace deformcd::gl::detail {

std::string gl_error_name(unsigned error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
      return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
      return "GL_STACK_OVERFLOW";
    default: {
      std::ostringstream hex;
      hex << "GL error 0x" << std::hex << error;
      return hex.str();
    }
  }
}

void throw_if_gl_error(const char* call, const char* file, int line) {
  GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  std::string names;
  // GL may hold several error flags; drain them all so the next check starts clean. The bound
  // guards against a lost context, which keeps reporting errors forever.
  for (int i = 0; i < 8 && error != GL_NO_ERROR; ++i, error = glGetError()) {
    if (!names.empty()) names += ", ";
    names += gl_error_name(error);
  }
  std::string message = std::string(file) + ":" + std::to_string(line) + ": " + names + " after " +
                        call + " (or an earlier unchecked GL call)";
  if (DebugMessageLog* log = DebugMessageLog::of_current_context()) {
    for (const std::string& m : log->take())
      message += "\n  " + m;
  }
  throw GlError(message);
}

}  // namespace deformcd::gl::detail
