#pragma once
// Collects a debug context's KHR_debug error messages so that GlError messages can quote the
// driver's explanation, not just the error enum. Synchronous output keeps each message on the
// thread and at the call that caused it.

#include <cstddef>
#include <string>
#include <vector>

namespace deformcd::gl::detail {

class DebugMessageLog {
 public:
  DebugMessageLog() = default;
  DebugMessageLog(const DebugMessageLog&) = delete;
  DebugMessageLog& operator=(const DebugMessageLog&) = delete;

  // Routes the current context's GL_DEBUG_TYPE_ERROR messages (except the shader compiler's)
  // into this log. The log must stay at its address for as long as the context is used.
  void install();

  // The messages collected since the last call, oldest first.
  [[nodiscard]] std::vector<std::string> take();

  // The log installed on the current context, or nullptr when it has none of ours (an adopted
  // context keeps the application's callback).
  [[nodiscard]] static DebugMessageLog* of_current_context();

  void add(std::string message);

 private:
  // A context stuck in an error loop must not grow the log without bound.
  static constexpr std::size_t kMaxMessages = 16;
  std::vector<std::string> messages_;
  std::size_t dropped_ = 0;
};

}  // namespace deformcd::gl::detail
