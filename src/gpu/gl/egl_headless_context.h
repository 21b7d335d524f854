#pragma once
// A core-profile context with no surface on an EGL display of either headless platform
// (device or surfaceless); the platforms differ only in how they find the display.

#include <epoxy/egl.h>

#include <memory>
#include <string>

#include "deformcd/gl/context.h"
#include "gpu/gl/egl_display.h"
#include "gpu/gl/gl_debug_log.h"

namespace deformcd::gl::detail {

class EglHeadlessContext final : public Context {
 public:
  // Creates the newest core context from 4.6 down to 4.3 on `display` and makes it current.
  // Throws GlError saying what the display offers instead when none can be created.
  EglHeadlessContext(EglDisplay display, std::string platform_name, const std::string& details,
                     bool debug);
  ~EglHeadlessContext() override;

  void make_current() override;
  [[nodiscard]] std::string_view platform_name() const override { return platform_name_; }
  [[nodiscard]] std::string platform_details() const override { return details_; }

 private:
  void destroy() noexcept;

  EglDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string platform_name_;
  std::string details_;
  // Heap-allocated: the GL debug callback holds its address.
  std::unique_ptr<DebugMessageLog> debug_log_;
};

}  // namespace deformcd::gl::detail
