#pragma once
// An initialized EGL display, shared safely between contexts.
//
// EGL keeps one EGLDisplay per (platform, native display) for the whole process, and
// eglTerminate ends it for every user at once. Two deformcd contexts on the same platform (the
// tests' shared context and one a test makes itself, say) therefore share a display, and only
// the last one to go may terminate it: EglDisplay counts references per display.

#include <epoxy/egl.h>

#include <string>
#include <string_view>

namespace deformcd::gl::detail {

class EglDisplay {
 public:
  // Initializes `display` (from eglGetPlatformDisplayEXT). Throws GlError naming the EGL error.
  explicit EglDisplay(EGLDisplay display);
  ~EglDisplay();
  EglDisplay(EglDisplay&& other) noexcept;
  EglDisplay& operator=(EglDisplay&&) = delete;
  EglDisplay(const EglDisplay&) = delete;
  EglDisplay& operator=(const EglDisplay&) = delete;

  [[nodiscard]] EGLDisplay get() const noexcept { return display_; }
  [[nodiscard]] bool has_extension(const char* name) const;
  // "EGL 1.5 (Mesa Project)".
  [[nodiscard]] std::string description() const;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
};

// "EGL_BAD_MATCH"... for an eglGetError code.
[[nodiscard]] std::string egl_error_name(EGLint error);

// Whether the EGL client extension string (EGL_NO_DISPLAY) lists `name`.
[[nodiscard]] bool has_egl_client_extension(const char* name);

// Whether a space-separated extension list contains `name` (false for a null list).
[[nodiscard]] bool extension_listed(const char* list, std::string_view name);

}  // namespace deformcd::gl::detail
