#pragma once
// Which backend a world or a detector runs on and the GL context it runs in (kAuto is decided
// here), and the GL backend's objects. The only place that knows whether the GL backend was
// compiled in: the build compiles backend_choice_gl.cpp or, without the GL backend,
// backend_choice_none.cpp, whose functions throw GlError. The Detector, the World's simulation
// factory and the GL probe make every GL object through the functions below, with no #ifdef.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/backend.h"

namespace deformcd {

namespace gl {
class Context;
class GlProximity;
}  // namespace gl
namespace collision {
class CollisionBackend;
struct CollisionData;
struct ProximityCandidate;
}  // namespace collision
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

/// The GL collision backend, in `context`.
[[nodiscard]] std::unique_ptr<collision::CollisionBackend> make_gl_collision(gl::Context& context);

/// Deletes a GL proximity search (its type is complete where the GL backend is built).
struct GlProximityDeleter {
  void operator()(gl::GlProximity* search) const;
};
using GlProximityPtr = std::unique_ptr<gl::GlProximity, GlProximityDeleter>;

/// The GL proximity search over `data`'s meshes, in `context`.
[[nodiscard]] GlProximityPtr make_gl_proximity(gl::Context& context,
                                               const collision::CollisionData& data);

/// Whether `backend` is the GL collision backend (make_gl_collision), whose trees and positions
/// a GL proximity search reads. False in a build without the GL backend.
[[nodiscard]] bool is_gl_collision(const collision::CollisionBackend& backend) noexcept;

/// `search`'s candidates over the trees and positions of `backend` (a GL collision backend,
/// its context current), staged as a collision pass stages them.
[[nodiscard]] std::vector<collision::ProximityCandidate> find_gl_proximity(
    collision::CollisionBackend& backend, gl::GlProximity& search, std::span<const float> reach,
    std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs);

/// The GL mass-spring simulation, in `context`.
[[nodiscard]] std::unique_ptr<sim::SimulationBackend> make_gl_simulation(gl::Context& context);

/// The GL contact response that corrects `simulation` (made by make_gl_simulation in the same
/// context) in place.
[[nodiscard]] std::unique_ptr<response::ResponseBackend> make_gl_response(
    gl::Context& context, sim::SimulationBackend& simulation);

}  // namespace deformcd
