#pragma once
// The two headless EGL platforms. Each either returns a current 4.3+ core context or throws
// GlError saying why it cannot; context_factory.cpp tries them in order.

#include <memory>

#include "deformcd/gl/context.h"

namespace deformcd::gl::detail {

// Which devices of the device platform to try. Mesa lists llvmpipe as a "software" device
// (EGL_MESA_device_software); the automatic order tries hardware first, then the surfaceless
// platform, and software devices last, since surfaceless gives the same llvmpipe.
enum class DeviceSelection { kHardwareOnly, kSoftwareOnly, kAny };

// EGL_EXT_platform_device: a GPU without any display server.
[[nodiscard]] std::unique_ptr<Context> create_device_platform_context(DeviceSelection selection,
                                                                      bool debug);

// EGL_MESA_platform_surfaceless: Mesa's pick of render node, or llvmpipe without one.
[[nodiscard]] std::unique_ptr<Context> create_surfaceless_platform_context(bool debug);

}  // namespace deformcd::gl::detail
