#pragma once
// Chooses and creates the simulation and collision backends of a world. The only place that knows
// whether the GL backend was compiled in (DEFORMCD_WITH_GL).

#include <memory>
#include <string>

#include "core/collision/collision_backend.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/world.h"

namespace deformcd {

struct CreatedBackend {
  std::unique_ptr<gl::Context> owned_context;  ///< set when the world made its own context
  std::unique_ptr<sim::SimulationBackend> backend;
  std::unique_ptr<collision::CollisionBackend> collision;  ///< reads `backend`'s positions
  std::string notice;  ///< why kAuto fell back to the CPU, if it did
};

/// Creates the backend `options` ask for. kAuto tries GL and falls back to the CPU with a
/// notice; kGl throws GlError when no GL 4.3 context can be had.
[[nodiscard]] CreatedBackend create_backend(const WorldOptions& options);

}  // namespace deformcd
