#pragma once
/// \file context.h
/// The OpenGL 4.3+ core context deformcd's compute shaders run in: a headless EGL context it
/// creates itself, or a context the application already has current (e.g. a GLFW window).
/// Every other deformcd::gl call needs a context current on the calling thread.

#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace deformcd::gl {

/// Which EGL platform a headless context is created on.
enum class EglPlatform {
  kAuto,         ///< a GPU through the device platform, else Mesa's surfaceless platform
  kDevice,       ///< EGL_EXT_platform_device only (any device, software ones included)
  kSurfaceless,  ///< EGL_MESA_platform_surfaceless only (llvmpipe when there is no GPU)
};

/// Parses "auto", "device" or "surfaceless"; throws GlError naming `origin` otherwise.
[[nodiscard]] EglPlatform parse_egl_platform(std::string_view text,
                                             std::string_view origin = "EGL platform");

/// How a headless context is created.
struct ContextOptions {
  /// kAuto lets the environment variable DEFORMCD_EGL_PLATFORM (auto|device|surfaceless)
  /// choose; any other value is used as is and the variable is ignored.
  EglPlatform platform = EglPlatform::kAuto;
  /// Request a KHR_debug context and collect its error messages into GlError messages.
#ifdef NDEBUG
  bool debug = false;
#else
  bool debug = true;
#endif
};

/// An OpenGL 4.3+ core context. Move-only through unique_ptr; not thread-safe (GL contexts are
/// current on one thread at a time).
class Context {
 public:
  virtual ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  /// Makes this context current on the calling thread.
  virtual void make_current() = 0;
  /// "egl-device", "egl-surfaceless" or "adopted".
  [[nodiscard]] virtual std::string_view platform_name() const = 0;
  /// Human-readable details of the platform: EGL version and vendor, which device...
  [[nodiscard]] virtual std::string platform_details() const = 0;

 protected:
  Context() = default;
};

/// Creates a headless core-profile context, newest version first (4.6 down to 4.3), and makes
/// it current. Throws GlError when no platform gives 4.3; the message lists what was found and
/// why each platform failed.
[[nodiscard]] std::unique_ptr<Context> create_headless_context(const ContextOptions& options = {});

/// Wraps the context current on the calling thread (created by the application, e.g. with
/// GLFW) without owning it: destroying the wrapper leaves the context alone. make_current()
/// calls `make_current` when given; otherwise it re-binds the adopted EGL context, or does
/// nothing for other window systems (the application then keeps its context current).
/// Throws GlError when no context is current or it is older than 4.3.
[[nodiscard]] std::unique_ptr<Context> adopt_current_context(
    std::function<void()> make_current = {});

}  // namespace deformcd::gl
