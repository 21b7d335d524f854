// One undamped spring between two masses, stepped on the GPU, oscillates with the analytic
// period 2 pi sqrt(mu / k), mu = m1 m2 / (m1 + m2), about a fixed centre of mass.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include "deformcd/simulation_state.h"
#include "gl/gl_test_context.h"
#include "gl/sim_test_worlds.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

constexpr float kStiffness = 100.0f;  // N/m
constexpr float kMass1 = 1.0f;        // kg
constexpr float kMass2 = 3.0f;        // kg
constexpr float kRestLength = 0.5f;   // m
constexpr float kStretch = 0.1f;      // initial elongation, m

// The two-node world, along an axis that is not a coordinate axis.
SimulationState one_spring_world() {
  return test::two_mass_spring(kMass1, kMass2, kRestLength, kRestLength + kStretch, kStiffness,
                               glm::vec3(0.3f, -0.2f, 0.1f),
                               glm::normalize(glm::vec3(1.0f, 2.0f, 2.0f)));
}

class SpringOscillationTest : public test_support::GlTest {};

TEST_F(SpringOscillationTest, PeriodMatchesTheReducedMassFormula) {
  const double reduced_mass = double{kMass1} * kMass2 / (double{kMass1} + kMass2);
  const double period = 2.0 * std::numbers::pi * std::sqrt(reduced_mass / kStiffness);  // 0.544 s
  const float h = 1e-3f;
  const auto substeps = static_cast<int>(2.6 * period / h);

  const SimulationState world = one_spring_world();
  GlSimulation gl(context());
  gl.upload(world);
  const sim::SubstepConstants c = test::substep_constants(h);
  const auto centre_of_mass = [](const std::vector<glm::vec4>& x) {
    return (kMass1 * glm::vec3(x[0]) + kMass2 * glm::vec3(x[1])) / (kMass1 + kMass2);
  };
  const glm::vec3 initial_centre = centre_of_mass(world.positions);

  // Times at which the elongation changes sign, interpolated linearly between substeps.
  std::vector<double> crossings;
  std::vector<glm::vec4> x;
  double previous = kStretch;
  for (int step = 1; step <= substeps; ++step) {
    gl.substep(c);
    gl.download_positions(x);
    const double elongation = glm::distance(glm::vec3(x[0]), glm::vec3(x[1])) - kRestLength;
    if ((previous > 0.0) != (elongation > 0.0)) {
      crossings.push_back(h * (step - 1 + previous / (previous - elongation)));
    }
    previous = elongation;
  }
  ASSERT_GE(crossings.size(), 5u) << "in 2.6 periods the spring crosses its rest length 5 times";
  const double measured =
      2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  EXPECT_NEAR(measured, period, 0.01 * period);
  EXPECT_LT(glm::distance(centre_of_mass(x), initial_centre), 1e-5f);
}

}  // namespace
}  // namespace deformcd::gl
