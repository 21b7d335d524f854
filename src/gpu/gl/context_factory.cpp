// create_headless_context(): picks the EGL platform once, in a fixed order, and explains every
// failure when none works.

#include <epoxy/egl.h>

#include <cstdlib>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "gpu/gl/egl_platforms.h"

// LeakSanitizer's entry points, present only in sanitizer builds (weak: null otherwise). Their
// names are the sanitizer runtime's, hence reserved identifiers.
extern "C" void __lsan_disable() __attribute__((weak));  // NOLINT(bugprone-reserved-identifier)
extern "C" void __lsan_enable() __attribute__((weak));   // NOLINT(bugprone-reserved-identifier)

namespace deformcd::gl {

namespace {

// Mesa 22.3.6-1+deb12u2's EGL (Debian 12, llvmpipe) leaks 128 bytes once per process while a
// context is created, in a driver module it unloads at exit: LeakSanitizer then reports a frame
// in "<unknown module>", which no suppression can name, and every sanitizer build of a program
// that creates a context would fail on the driver's leak. Allocations made while the platform
// creates the context are therefore not leak-checked (ours are made after it).
class DriverLeaksIgnored {
 public:
  DriverLeaksIgnored() {
    if (__lsan_disable) __lsan_disable();
  }
  ~DriverLeaksIgnored() {
    if (__lsan_enable) __lsan_enable();
  }
  DriverLeaksIgnored(const DriverLeaksIgnored&) = delete;
  DriverLeaksIgnored& operator=(const DriverLeaksIgnored&) = delete;
};

constexpr const char* kPlatformVariable = "DEFORMCD_EGL_PLATFORM";

// The platform to use, and what chose it ("" when nothing forced one).
std::pair<EglPlatform, std::string> resolve_platform(const ContextOptions& options) {
  if (options.platform != EglPlatform::kAuto) {
    return {options.platform, "ContextOptions::platform"};
  }
  const char* value = std::getenv(kPlatformVariable);
  if (value == nullptr || *value == '\0') return {EglPlatform::kAuto, ""};
  const EglPlatform platform = parse_egl_platform(value, kPlatformVariable);
  return {platform, std::string(kPlatformVariable) + "=" + value};
}

struct Attempt {
  const char* label;
  std::function<std::unique_ptr<Context>()> create;
};

std::vector<Attempt> attempts_for(EglPlatform platform, bool debug) {
  using detail::DeviceSelection;
  auto device = [debug](DeviceSelection selection) {
    return [debug, selection] { return detail::create_device_platform_context(selection, debug); };
  };
  auto surfaceless = [debug] { return detail::create_surfaceless_platform_context(debug); };
  switch (platform) {
    case EglPlatform::kDevice:
      return {{"egl-device", device(DeviceSelection::kAny)}};
    case EglPlatform::kSurfaceless:
      return {{"egl-surfaceless", surfaceless}};
    case EglPlatform::kAuto:
      break;
  }
  return {{"egl-device", device(DeviceSelection::kHardwareOnly)},
          {"egl-surfaceless", surfaceless},
          {"egl-device (software devices)", device(DeviceSelection::kSoftwareOnly)}};
}

}  // namespace

EglPlatform parse_egl_platform(std::string_view text, std::string_view origin) {
  if (text == "auto") return EglPlatform::kAuto;
  if (text == "device") return EglPlatform::kDevice;
  if (text == "surfaceless") return EglPlatform::kSurfaceless;
  throw GlError(std::string(origin) + "='" + std::string(text) +
                "' is not one of auto, device, surfaceless");
}

std::unique_ptr<Context> create_headless_context(const ContextOptions& options) {
  const auto [platform, forced_by] = resolve_platform(options);
  std::string tried;
  if (!epoxy_has_egl()) {
    tried = "\n  libEGL.so.1 could not be loaded";
  } else {
    for (const Attempt& attempt : attempts_for(platform, options.debug)) {
      try {
        const DriverLeaksIgnored driver_only;
        return attempt.create();
      } catch (const GlError& e) {
        tried += std::string("\n  ") + attempt.label + ": " + e.what();
      }
    }
  }
  throw GlError(
      "no OpenGL 4.3 core context could be created, so the GPU backend is unavailable; the CPU "
      "backend (--backend cpu) remains available. Platforms tried" +
      (platform == EglPlatform::kAuto ? std::string() : " (forced by " + forced_by + ")") + ":" +
      tried);
}

}  // namespace deformcd::gl
