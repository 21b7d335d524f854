// The stable-substep estimate against the exact limit of the explicit step.

#include <cmath>

#include <gtest/gtest.h>

#include "core/sim/stability_estimate.h"
#include "cpu/cpu_simulation.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

// Two 0.5 kg masses on a 100 N/m spring released stretched by 1 cm, the spring's damping
// `damping` s x its stiffness.
SimulationState damped_pair(float damping) {
  SimulationState state = test::two_mass_spring(0.5f, 0.5f, 1.0f, 1.01f, 100.0f);
  state.body_params[0].damping = damping;
  return state;
}

// Largest |extension| of damped_pair(damping) over 2000 substeps of h.
float max_extension(float h, float damping = 0.0f) {
  cpu::CpuSimulation sim(1);
  sim.upload(damped_pair(damping));
  float largest = 0.0f;
  std::vector<glm::vec4> p;
  for (int step = 0; step < 2000; ++step) {
    sim.substep({h, glm::vec3(0.0f), 1.0f});
    sim.download_positions(p);
    largest = std::max(largest, std::abs(p[1].x - p[0].x - 1.0f));
  }
  return largest;
}

TEST(StabilityEstimate, IsExactForTwoEqualMasses) {
  // omega^2 = k (1/m1 + 1/m2) = 400, so symplectic Euler is stable for h < 2 / 20 = 0.1 s.
  const double h =
      sim::estimate_max_stable_substep(test::two_mass_spring(0.5f, 0.5f, 1.0f, 1.01f, 100.0f));
  EXPECT_NEAR(h, 0.1, 1e-6);
  EXPECT_LT(max_extension(static_cast<float>(0.95 * h)), 0.05f);  // bounded oscillation
  EXPECT_GT(max_extension(static_cast<float>(1.05 * h)), 1.0f);   // grows without bound
}

TEST(StabilityEstimate, IsExactForADampedPair) {
  // The mode: omega^2 = 400, damping rate c = 0.01 s x 400 = 4 / s. The explicit step is stable
  // while h^2 omega^2 + 2 h c <= 4: h < 4 / (c + sqrt(c^2 + 4 omega^2)) = 0.09053 s, not the
  // undamped 0.1 s (the advice without the damping: at 0.095 s this pair grows without bound).
  const double h = sim::estimate_max_stable_substep(damped_pair(0.01f));
  EXPECT_NEAR(h, 4.0 / (4.0 + std::sqrt(16.0 + 1600.0)), 1e-6);
  EXPECT_LT(max_extension(static_cast<float>(0.95 * h), 0.01f), 0.05f);
  EXPECT_GT(max_extension(static_cast<float>(1.05 * h), 0.01f), 1.0f);
  EXPECT_GT(max_extension(0.095f, 0.01f), 1.0f);
}

TEST(StabilityEstimate, IsConservativeForUnequalMasses) {
  // Exact limit 2 / sqrt(k (1/m1 + 1/m2)); the block bound may only be smaller.
  const float m1 = 0.1f, m2 = 2.0f, k = 50.0f;
  const double exact = 2.0 / std::sqrt(k * (1.0 / m1 + 1.0 / m2));
  const double h = sim::estimate_max_stable_substep(test::two_mass_spring(m1, m2, 1.0f, 1.0f, k));
  EXPECT_LE(h, exact);
  EXPECT_GT(h, 0.5 * exact);
}

}  // namespace
}  // namespace deformcd
