#pragma once
// The largest substep h the explicit step (symplectic Euler, the spring damping taken from the
// old velocity) is stable with, for the system linearized at rest: every mode of stiffness
// omega^2 and damping rate c needs h^2 omega^2 + 2 h c <= 4 (the Jury condition of the step's
// 2 x 2 amplification; c = 0 gives the familiar h < 2 / omega). Applied to the mass-weighted
// matrix h^2 K + 2 h C (springs and tetrahedron volume terms in K, the springs' stiffness-
// proportional damping in C), whose largest eigenvalue block Gershgorin bounds row by row, it
// errs on the safe side. Not covered: the nonlinear terms (a spring compressed below half its
// rest length is stiffer across than along), so a large deformation can need more; the global
// velocity damping only helps.

#include "deformcd/simulation_state.h"

namespace deformcd::sim {

/// Seconds; +infinity for a world with nothing stiff (no springs, no tetrahedra).
[[nodiscard]] double estimate_max_stable_substep(const SimulationState& world);

}  // namespace deformcd::sim
