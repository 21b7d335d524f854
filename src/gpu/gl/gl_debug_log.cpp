#include "gpu/gl/gl_debug_log.h"

#include <epoxy/gl.h>

#include <utility>

namespace deformcd::gl::detail {

namespace {

void GLAPIENTRY on_debug_message(GLenum source, GLenum type, GLuint id, GLenum /*severity*/,
                                 GLsizei length, const GLchar* message, const void* user) {
  // Only errors, which come with a glGetError flag for DEFORMCD_GL_CHECK to report. Compiler
  // errors are left out: ComputeProgram reports the shader's info log, mapped to file names.
  if (type != GL_DEBUG_TYPE_ERROR || source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
  auto* log = static_cast<DebugMessageLog*>(const_cast<void*>(user));
  std::string text =
      length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : std::string(message);
  log->add("KHR_debug #" + std::to_string(id) + ": " + text);
}

}  // namespace

void DebugMessageLog::install() {
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(on_debug_message, this);
}

void DebugMessageLog::add(std::string message) {
  if (messages_.size() >= kMaxMessages) {
    ++dropped_;
    return;
  }
  messages_.push_back(std::move(message));
}

std::vector<std::string> DebugMessageLog::take() {
  std::vector<std::string> out = std::exchange(messages_, {});
  if (dropped_ > 0) {
    // Appended piecewise: "literal" + std::string&& trips GCC 12's -Wrestrict at -O3.
    std::string note = "(";
    note += std::to_string(dropped_);
    note += " more KHR_debug messages dropped)";
    out.push_back(std::move(note));
    dropped_ = 0;
  }
  return out;
}

DebugMessageLog* DebugMessageLog::of_current_context() {
  void* callback = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
  if (callback != reinterpret_cast<void*>(&on_debug_message)) return nullptr;
  void* user = nullptr;
  glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
  return static_cast<DebugMessageLog*>(user);
}

}  // namespace deformcd::gl::detail
