#pragma once
// One line naming the GL device, for the backends' device() (GlSimulation, GlCollision).

#include <string>

#include "deformcd/gl/device_info.h"

namespace deformcd::gl {

// "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6, surfaceless".
[[nodiscard]] inline std::string device_summary(const DeviceInfo& info) {
  return info.renderer + ", OpenGL " + info.gl_version + ", " + info.platform;
}

}  // namespace deformcd::gl
