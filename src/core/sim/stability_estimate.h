#pragma once
// An estimate of the largest substep the explicit (symplectic Euler) step stays stable with:
// h < 2 / omega_max, omega_max^2 bounded by block Gershgorin on the mass-weighted stiffness
// matrix of the springs and tetrahedron volume terms at rest. The bound overestimates
// omega_max, so the estimate errs on the safe side (the true limit is usually 1-2x larger).

#include "deformcd/simulation_state.h"

namespace deformcd::sim {

/// Seconds; +infinity for a world with nothing stiff (no springs, no tetrahedra).
[[nodiscard]] double estimate_max_stable_substep(const SimulationState& world);

}  // namespace deformcd::sim
