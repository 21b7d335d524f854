#pragma once
// Which backend a world or a detector runs on and the GL context it runs in (kAuto is decided
// here), and the GL backend's objects. The only place that knows whether the GL backend was
// compiled in: the build compiles backend_choice_gl.cpp or, without the GL backend,
// backend_choice_none.cpp, whose functions throw GlError. The Detector, the World's simulation
// factory and the GL probe make every GL object through the functions below, with no #ifdef.

#include <memory>
#include <string>

#include "deformcd/backend.h"

namespace deformcd {

namespace gl {
class Context;
}  // namespace gl
namespace collision {
class CollisionBackend;
}  // namespace collision
namespace cpu {
class Executor;
}  // namespace cpu
namespace sim {
class SimulationBackend;
}
namespace response {
class ResponseBackend;
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

// The GL backend's objects (backend_choice_gl.cpp). Without the GL backend
// (backend_choice_none.cpp), each function below that makes or runs one throws GlError ("this
// deformcd was built without the OpenGL backend").

/// Whether this build has the GL backend.
[[nodiscard]] bool gl_backend_built() noexcept;

/// A new headless context (gl::create_headless_context), not made current.
[[nodiscard]] std::unique_ptr<gl::Context> make_headless_gl_context();

/// `context`'s GL_RENDERER (the context current).
[[nodiscard]] std::string gl_renderer(gl::Context& context);

/// The GL_RENDERER of a new headless context (made current, then destroyed): what the probe's
/// child process asks.
[[nodiscard]] std::string headless_gl_renderer();

/// The GL collision backend, in `context`; a widened proximity search runs on `executor`'s
/// threads.
[[nodiscard]] std::unique_ptr<collision::CollisionBackend> make_gl_collision(
    gl::Context& context, const std::shared_ptr<cpu::Executor>& executor);

/// The GL mass-spring simulation, in `context`.
[[nodiscard]] std::unique_ptr<sim::SimulationBackend> make_gl_simulation(gl::Context& context);

/// The GL contact response that corrects `simulation` (made by make_gl_simulation in the same
/// context) in place.
[[nodiscard]] std::unique_ptr<response::ResponseBackend> make_gl_response(
    gl::Context& context, sim::SimulationBackend& simulation);

}  // namespace deformcd
