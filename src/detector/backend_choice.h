#pragma once
// Which backend a world or a detector runs on, and the GL context it runs in. The only place
// that knows whether the GL backend was compiled in (DEFORMCD_HAS_GL) and that decides kAuto.

#include <memory>
#include <string>

#include "deformcd/backend.h"

namespace deformcd {

namespace gl {
class Context;
}

struct BackendChoice {
  BackendKind kind = BackendKind::kCpu;        ///< kGl or kCpu
  std::unique_ptr<gl::Context> owned_context;  ///< set when a headless context was created
  gl::Context* context = nullptr;              ///< the context to run in (kGl)
  std::string notice;                          ///< why kAuto chose the CPU, if it did
};

/// kCpu as is; kGl in `context` (or a new headless one; GlError when none can be had); kAuto
/// GL on a hardware device, else the CPU with a notice: no GL 4.3, or only a software
/// rasterizer (llvmpipe, softpipe, swrast), on which the CPU backend is several times faster.
[[nodiscard]] BackendChoice choose_backend(BackendKind kind, gl::Context* context);

/// Whether a GL_RENDERER string names a software rasterizer.
[[nodiscard]] bool is_software_renderer(const std::string& renderer);

}  // namespace deformcd
