// adopt_current_context(): a Context for a context the application created and owns.

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <functional>
#include <memory>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "gpu/gl/egl_display.h"

namespace deformcd::gl {

namespace {

// The EGL state to restore in make_current(), when the adopted context is an EGL one.
struct EglBinding {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface draw = EGL_NO_SURFACE;
  EGLSurface read = EGL_NO_SURFACE;
};

class AdoptedContext final : public Context {
 public:
  AdoptedContext(std::function<void()> make_current, EglBinding egl, std::string details)
      : make_current_(std::move(make_current)), egl_(egl), details_(std::move(details)) {}

  void make_current() override {
    if (make_current_) {
      make_current_();
    } else if (egl_.context != EGL_NO_CONTEXT &&
               eglMakeCurrent(egl_.display, egl_.draw, egl_.read, egl_.context) != EGL_TRUE) {
      throw GlError("adopted EGL context: eglMakeCurrent failed: " +
                    detail::egl_error_name(eglGetError()));
    }
  }
  [[nodiscard]] std::string_view platform_name() const override { return "adopted"; }
  [[nodiscard]] std::string platform_details() const override { return details_; }

 private:
  std::function<void()> make_current_;
  EglBinding egl_;
  std::string details_;
};

}  // namespace

std::unique_ptr<Context> adopt_current_context(std::function<void()> make_current) {
  EglBinding egl;
  // Only ask EGL when libEGL is there: epoxy aborts on a missing library rather than failing.
  if (epoxy_has_egl() && eglGetCurrentContext() != EGL_NO_CONTEXT) {
    egl = {eglGetCurrentDisplay(), eglGetCurrentContext(), eglGetCurrentSurface(EGL_DRAW),
           eglGetCurrentSurface(EGL_READ)};
  }
  // Without a current context the GL dispatch returns null here.
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (version == nullptr) {
    throw GlError("adopt_current_context: no OpenGL context is current on this thread");
  }
  if (!epoxy_is_desktop_gl() || epoxy_gl_version() < 43) {
    throw GlError(std::string("adopt_current_context: the current context is GL ") + version +
                  "; deformcd needs desktop OpenGL 4.3 or newer (the CPU backend, --backend "
                  "cpu, remains available)");
  }
  std::string details =
      egl.context != EGL_NO_CONTEXT ? "application's EGL context" : "application's context";
  return std::make_unique<AdoptedContext>(std::move(make_current), egl, std::move(details));
}

}  // namespace deformcd::gl
