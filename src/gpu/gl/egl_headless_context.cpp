#include "gpu/gl/egl_headless_context.h"

#include <epoxy/gl.h>

#include <array>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "gpu/gl/fault_injection.h"

namespace deformcd::gl::detail {

namespace {

constexpr int kMinMinor = 3;  // 4.3: compute shaders and SSBOs are core
constexpr int kMaxMinor = 6;

EGLConfig choose_config(const EglDisplay& display) {
  // Without a surface the config matters little; skip it where EGL allows.
  if (display.has_extension("EGL_KHR_no_config_context")) return EGL_NO_CONFIG_KHR;
  const std::array<EGLint, 5> attributes = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                            EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display.get(), attributes.data(), &config, 1, &count) != EGL_TRUE ||
      count == 0) {
    throw GlError(display.description() + ": no EGL config renders desktop OpenGL (" +
                  egl_error_name(eglGetError()) + ")");
  }
  return config;
}

EGLContext try_core_context(const EglDisplay& display, EGLConfig config, int minor, bool debug) {
  std::vector<EGLint> attributes = {
      EGL_CONTEXT_MAJOR_VERSION_KHR,       4,
      EGL_CONTEXT_MINOR_VERSION_KHR,       minor,
      EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
  if (debug)
    attributes.insert(attributes.end(), {EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
  attributes.push_back(EGL_NONE);
  return eglCreateContext(display.get(), config, EGL_NO_CONTEXT, attributes.data());
}

// The GL version a context with default attributes gets: what to tell the user when 4.3 core
// cannot be had. Leaves no context current.
std::string best_available_version(const EglDisplay& display, EGLConfig config) {
  const std::array<EGLint, 1> no_attributes = {EGL_NONE};
  EGLContext context =
      eglCreateContext(display.get(), config, EGL_NO_CONTEXT, no_attributes.data());
  if (context == EGL_NO_CONTEXT) return "none (" + egl_error_name(eglGetError()) + ")";
  std::string version = "unknown";
  if (eglMakeCurrent(display.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, context) == EGL_TRUE) {
    const auto* text = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    if (text != nullptr) version = std::string("GL ") + text;
    eglMakeCurrent(display.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display.get(), context);
  return version;
}

}  // namespace

EglHeadlessContext::EglHeadlessContext(EglDisplay display, std::string platform_name,
                                       const std::string& details, bool debug)
    : display_(std::move(display)),
      platform_name_(std::move(platform_name)),
      details_(display_.description() + (details.empty() ? "" : ", " + details)) {
  // Making a context current without a surface needs this extension.
  if (!display_.has_extension("EGL_KHR_surfaceless_context")) {
    throw GlError(details_ + ": EGL_KHR_surfaceless_context is missing");
  }
  if (!display_.has_extension("EGL_KHR_create_context")) {
    throw GlError(details_ + ": EGL_KHR_create_context is missing (no core profiles)");
  }
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    throw GlError(details_ + ": no desktop OpenGL (eglBindAPI: " + egl_error_name(eglGetError()) +
                  ")");
  }
  const EGLConfig config = choose_config(display_);

  std::string last_error;
  // A driver may refuse debug contexts; a context without KHR_debug output beats none.
  for (const bool with_debug : {debug, false}) {
    for (int minor = kMaxMinor; minor >= kMinMinor && context_ == EGL_NO_CONTEXT; --minor) {
      context_ = try_core_context(display_, config, minor, with_debug);
      if (context_ == EGL_NO_CONTEXT) last_error = egl_error_name(eglGetError());
    }
    if (context_ != EGL_NO_CONTEXT || !debug) break;
  }
  if (context_ == EGL_NO_CONTEXT) {
    throw GlError(details_ + ": no core context 4.6..4.3 (eglCreateContext: " + last_error +
                  "); the best this platform offers is " +
                  best_available_version(display_, config));
  }
  try {
    make_current();
    // Trust but verify: 4.3 is what every deformcd shader is written against.
    if (epoxy_gl_version() < 43) {
      const auto* text = reinterpret_cast<const char*>(glGetString(GL_VERSION));
      throw GlError(details_ + ": asked for a 4.3+ core context, got GL " +
                    (text ? text : "(no version)"));
    }
  } catch (...) {
    destroy();  // the destructor does not run for a constructor that throws
    throw;
  }
  GLint flags = 0;
  glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
  if ((flags & GL_CONTEXT_FLAG_DEBUG_BIT) != 0) {
    debug_log_ = std::make_unique<DebugMessageLog>();
    debug_log_->install();
  }
}

EglHeadlessContext::~EglHeadlessContext() {
  destroy();
}

void EglHeadlessContext::destroy() noexcept {
  if (context_ == EGL_NO_CONTEXT) return;
  if (eglGetCurrentContext() == context_) {
    eglMakeCurrent(display_.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display_.get(), context_);
  context_ = EGL_NO_CONTEXT;
}

void EglHeadlessContext::make_current() {
  // On failure EGL leaves the calling thread's current context as it was.
  if (fault::should_fail(fault::Kind::kMakeCurrent)) {
    throw GlError("making the " + platform_name_ + " context current failed (" + details_ +
                  "): eglMakeCurrent: EGL_BAD_ACCESS (injected by gl::fault)");
  }
  if (eglMakeCurrent(display_.get(), EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
    throw GlError("making the " + platform_name_ + " context current failed (" + details_ +
                  "): eglMakeCurrent: " + egl_error_name(eglGetError()));
  }
}

}  // namespace deformcd::gl::detail
