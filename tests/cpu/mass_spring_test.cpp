// The CPU mass-spring step against physics: oscillation period, momentum, determinism.

#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "cpu/cpu_simulation.h"
#include "cpu/parallel_for.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

constexpr float kPi = 3.14159265358979f;

sim::SubstepConstants free_flight(float h) {
  return {h, glm::vec3(0.0f), 1.0f};
}

TEST(CpuMassSpring, TwoMassesOscillateWithTheReducedMassPeriod) {
  const float m1 = 0.3f, m2 = 0.7f, k = 50.0f;
  const float reduced = m1 * m2 / (m1 + m2);
  const float period = 2.0f * kPi * std::sqrt(reduced / k);
  const float h = period / 2000.0f;
  cpu::CpuSimulation sim(1);
  sim.upload(test::two_mass_spring(m1, m2, 1.0f, 1.2f, k));
  // Time the upward zero crossings of the extension (length - rest) over several periods.
  std::vector<float> crossings;
  float previous = 0.2f;
  std::vector<glm::vec4> p;
  for (int step = 1; step <= 20000; ++step) {
    sim.substep(free_flight(h));
    sim.download_positions(p);
    const float extension = (p[1].x - p[0].x) - 1.0f;
    if (previous < 0.0f && extension >= 0.0f) {
      crossings.push_back((static_cast<float>(step - 1) + previous / (previous - extension)) * h);
    }
    previous = extension;
  }
  ASSERT_GE(crossings.size(), 5u);
  const float measured =
      (crossings.back() - crossings.front()) / static_cast<float>(crossings.size() - 1);
  EXPECT_NEAR(measured, period, 0.01f * period);
}

// A cube grid with random stretches and random velocities, no gravity, no damping.
SimulationState shaken_grid(unsigned seed) {
  BodyOptions options;
  options.stiffness = 5.0e4;
  BodyInit init;
  init.body = build_body(test::tet_grid(4, 3, 3, 0.1), options);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.02f, 0.02f), speed(-0.5f, 0.5f);
  for (auto& p : init.body.positions)
    p += glm::vec4(jitter(rng), jitter(rng), jitter(rng), 0.0f);
  for (auto& v : init.body.velocities)
    v = glm::vec4(speed(rng), speed(rng), speed(rng), 0.0f);
  return assemble_simulation({init});
}

glm::dvec3 momentum(const std::vector<glm::vec4>& p, const std::vector<glm::vec4>& v) {
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    sum += glm::dvec3(v[i]) / static_cast<double>(p[i].w);
  return sum;
}

TEST(CpuMassSpring, MomentumIsConservedWithoutGravityAndDamping) {
  cpu::CpuSimulation sim;
  sim.upload(shaken_grid(7));
  std::vector<glm::vec4> p, v;
  sim.download_positions(p);
  sim.download_velocities(v);
  const glm::dvec3 start = momentum(p, v);
  double scale = 0.0;  // sum of |m v|, the size of the momenta that cancel
  for (std::size_t i = 0; i < p.size(); ++i)
    scale += glm::length(glm::dvec3(v[i])) / p[i].w;
  for (int step = 0; step < 1000; ++step)
    sim.substep(free_flight(1e-4f));
  sim.download_positions(p);
  sim.download_velocities(v);
  EXPECT_LT(glm::length(momentum(p, v) - start), 1e-5 * scale);
}

TEST(CpuMassSpring, OneAndTwoThreadsGiveBitIdenticalStates) {
  // Large enough to be split across threads (parallel_for's grain is 2048 elements).
  BodyInit big;
  big.body = build_body(test::tet_grid(12, 10, 10, 0.1));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> jitter(-0.01f, 0.01f);
  for (auto& p : big.body.positions)
    p += glm::vec4(jitter(rng), jitter(rng), jitter(rng), 0.0f);
  const SimulationState start = assemble_simulation({big});
  ASSERT_GT(start.springs.size(), 4 * cpu::kDefaultGrain);

  auto run = [&](int threads) {
    cpu::CpuSimulation sim(threads);
    sim.upload(start);
    for (int step = 0; step < 50; ++step)
      sim.substep({1e-3f, glm::vec3(0, -9.81f, 0), 0.999f});
    std::vector<glm::vec4> p;
    sim.download_positions(p);
    return p;
  };
  const std::vector<glm::vec4> one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(glm::vec4)), 0);
  EXPECT_NE(std::memcmp(one.data(), start.positions.data(), one.size() * sizeof(glm::vec4)), 0);
}

TEST(CpuMassSpring, FixedNodesStayAndCarryVelocityMovesTheBody) {
  BodyInit init;
  init.body = build_body(test::tet_grid(2, 2, 2, 0.1));
  init.fixed = {0};
  init.carry_velocity = glm::vec3(1.0f, 0.0f, 0.0f);
  cpu::CpuSimulation sim;
  sim.upload(assemble_simulation({init}));
  for (int step = 0; step < 100; ++step)
    sim.substep({0.01f, glm::vec3(0.0f), 1.0f});
  std::vector<glm::vec4> p;
  sim.download_positions(p);
  // Node 0 is fixed in the body's frame, which moves at 1 m/s for 1 s.
  EXPECT_NEAR(p[0].x, 1.0f, 1e-5f);
  EXPECT_NEAR(p[0].y, 0.0f, 1e-6f);
  EXPECT_EQ(p[0].w, 0.0f);
}

}  // namespace
}  // namespace deformcd
