// Mesa's surfaceless EGL platform: no window system and no device enumeration; Mesa picks a
// render node, or llvmpipe when there is none (as on a machine without a GPU).

#include <epoxy/egl.h>

#include "deformcd/error.h"
#include "gpu/gl/egl_display.h"
#include "gpu/gl/egl_headless_context.h"
#include "gpu/gl/egl_platforms.h"

namespace deformcd::gl::detail {

std::unique_ptr<Context> create_surfaceless_platform_context(bool debug) {
  for (const char* extension : {"EGL_EXT_platform_base", "EGL_MESA_platform_surfaceless"}) {
    if (!has_egl_client_extension(extension)) {
      throw GlError(std::string("EGL client extension ") + extension + " is missing");
    }
  }
  EglDisplay display(
      eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
  return std::make_unique<EglHeadlessContext>(std::move(display), "egl-surfaceless", "", debug);
}

}  // namespace deformcd::gl::detail
