#include "gpu/gl/egl_display.h"

#include <map>
#include <mutex>
#include <sstream>
#include <utility>

#include "deformcd/error.h"

namespace deformcd::gl::detail {

namespace {

// Process-wide because EGL's displays are: see egl_display.h.
struct DisplayReferences {
  std::mutex mutex;
  std::map<EGLDisplay, int> counts;
};

DisplayReferences& display_references() {
  static DisplayReferences references;
  return references;
}

}  // namespace

EglDisplay::EglDisplay(EGLDisplay display) {
  if (display == EGL_NO_DISPLAY) {
    throw GlError("eglGetPlatformDisplayEXT failed: " + egl_error_name(eglGetError()));
  }
  DisplayReferences& refs = display_references();
  std::lock_guard lock(refs.mutex);
  int& count = refs.counts[display];
  if (count == 0) {
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
      const EGLint error = eglGetError();
      refs.counts.erase(display);
      throw GlError("eglInitialize failed: " + egl_error_name(error));
    }
  }
  ++count;
  display_ = display;
}

EglDisplay::EglDisplay(EglDisplay&& other) noexcept
    : display_(std::exchange(other.display_, EGL_NO_DISPLAY)) {}

EglDisplay::~EglDisplay() {
  if (display_ == EGL_NO_DISPLAY) return;
  DisplayReferences& refs = display_references();
  std::lock_guard lock(refs.mutex);
  auto it = refs.counts.find(display_);
  if (it != refs.counts.end() && --it->second == 0) {
    refs.counts.erase(it);
    eglTerminate(display_);
  }
}

bool EglDisplay::has_extension(const char* name) const {
  return extension_listed(eglQueryString(display_, EGL_EXTENSIONS), name);
}

std::string EglDisplay::description() const {
  const char* version = eglQueryString(display_, EGL_VERSION);
  const char* vendor = eglQueryString(display_, EGL_VENDOR);
  return std::string("EGL ") + (version ? version : "?") + " (" + (vendor ? vendor : "?") + ")";
}

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
      return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
      return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default: {
      std::ostringstream hex;
      hex << "EGL error 0x" << std::hex << error;
      return hex.str();
    }
  }
}

bool has_egl_client_extension(const char* name) {
  // Null when EGL_EXT_client_extensions itself is missing.
  return extension_listed(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name);
}

bool extension_listed(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view rest(list);
  while (!rest.empty()) {
    const std::size_t end = rest.find(' ');
    if (rest.substr(0, end) == name) return true;
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  return false;
}

}  // namespace deformcd::gl::detail
