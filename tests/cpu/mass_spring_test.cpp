// The CPU mass-spring step against physics: oscillation period, momentum, determinism.

#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>

#include "core/sim/mass_spring.h"
#include "core/sim/node_force_lists.h"
#include "cpu/cpu_simulation.h"
#include "cpu/mass_spring_batch.h"
#include "cpu/parallel_for.h"
#include "support/world_fixtures.h"

namespace deformcd {
namespace {

constexpr float kPi = 3.14159265358979f;

sim::SubstepConstants free_flight(float h) {
  return {h, glm::vec3(0.0f), 1.0f};
}

bool same_bits(const glm::vec3& x, const glm::vec3& y) {
  return std::memcmp(&x, &y, sizeof(x)) == 0;
}

// spring_force = spring_term(spring_edge_state, +k) bit for bit; -k, or the ends swapped, give
// its exact negation; and the SIMD batch functions equal the scalar ones lane by lane.
TEST(CpuMassSpring, EdgeStateAndTermSplitTheSpringForceExactly) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f), positive(0.01f, 2.0f);
  std::vector<glm::vec4> x, v;
  std::vector<std::uint32_t> a, b;
  std::vector<float> rest, damping;
  for (std::uint32_t i = 0; i < 4 * cpu::kBatch; ++i) {
    x.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng), 1.0f);
    v.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng), 0.0f);
  }
  x[5] = x[4];  // a collapsed edge
  for (std::uint32_t e = 0; e < 2 * cpu::kBatch; ++e) {
    a.push_back(2 * e);
    b.push_back(2 * e + 1);
    rest.push_back(positive(rng));
    damping.push_back(positive(rng) * 1e-3f);
  }
  std::vector<glm::vec4> batch(a.size());
  for (std::size_t e = 0; e < a.size(); e += cpu::kBatch) {
    cpu::spring_edge_states(x.data(), v.data(), &a[e], &b[e], &rest[e], &damping[e], &batch[e]);
  }
  for (std::size_t e = 0; e < a.size(); ++e) {
    const glm::vec3 xa(x[a[e]]), xb(x[b[e]]), va(v[a[e]]), vb(v[b[e]]);
    const float k = positive(rng) * 100.0f;
    const glm::vec4 state = sim::spring_edge_state(xa, xb, va, vb, rest[e], damping[e]);
    const glm::vec4 swapped = sim::spring_edge_state(xb, xa, vb, va, rest[e], damping[e]);
    const glm::vec3 force = sim::spring_force(xa, xb, va, vb, rest[e], k, damping[e]);
    EXPECT_EQ(std::memcmp(&state, &batch[e], sizeof(state)), 0) << "edge " << e;
    EXPECT_TRUE(same_bits(sim::spring_term(state, k), force)) << "edge " << e;
    if (e == 2) continue;  // collapsed: +0 where -force is -0, which no sum can tell apart
    EXPECT_TRUE(same_bits(sim::spring_term(state, -k), -force)) << "edge " << e;
    EXPECT_TRUE(same_bits(sim::spring_term(swapped, k), -force)) << "edge " << e;
  }
  EXPECT_EQ(batch[2], glm::vec4(0.0f)) << "the collapsed edge (nodes 4 and 5)";
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

// The passes as the state describes them (and the GL shaders run them): every spring's force
// into spring_forces, every tetrahedron's corners into tet_forces, each node gathering both over
// its lists; serial, one element at a time.
void reference_substep(SimulationState& w, const sim::SubstepConstants& c) {
  for (std::size_t s = 0; s < w.springs.size(); ++s) {
    const gpu::Spring& spring = w.springs[s];
    const gpu::BodyParams& p = w.body_params[w.node_body[spring.a]];
    w.spring_forces[s] = glm::vec4(
        sim::spring_force(glm::vec3(w.positions[spring.a]), glm::vec3(w.positions[spring.b]),
                          glm::vec3(w.velocities[spring.a]), glm::vec3(w.velocities[spring.b]),
                          spring.rest_length, spring.stiffness, p.damping),
        0.0f);
  }
  for (std::size_t t = 0; t < w.tets.size(); ++t) {
    const gpu::Tetra& tet = w.tets[t];
    if (tet.stiffness == 0.0f) continue;
    glm::vec3 f[4];
    sim::tet_volume_forces(glm::vec3(w.positions[tet.a]), glm::vec3(w.positions[tet.b]),
                           glm::vec3(w.positions[tet.c]), glm::vec3(w.positions[tet.d]),
                           tet.rest_volume, tet.stiffness, f);
    for (std::size_t k = 0; k < 4; ++k)
      w.tet_forces[4 * t + k] = glm::vec4(f[k], 0.0f);
  }
  for (std::size_t i = 0; i < w.positions.size(); ++i) {
    const glm::vec3 f =
        sim::gather_node_force(w.node_spring_list.data(), w.node_spring_offset[i],
                               w.node_spring_offset[i + 1], w.spring_forces.data()) +
        sim::gather_tet_force(w.node_tet_list.data(), w.node_tet_offset[i],
                              w.node_tet_offset[i + 1], w.tet_forces.data());
    w.forces[i] = glm::vec4(f, 0.0f);
    sim::integrate_node(w.positions[i], w.velocities[i], f,
                        glm::vec3(w.body_params[w.node_body[i]].carry_velocity), c);
  }
}

// Two shaken bodies, one with volume forces and one without (its tetrahedra skipped), damped,
// one with fixed nodes and one carried; every other spring has its ends swapped, so that edges
// carry springs of both orientations. Large enough for every pass to be split across threads.
SimulationState two_shaken_bodies() {
  std::vector<BodyInit> bodies(2);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> jitter(-0.02f, 0.02f), speed(-0.5f, 0.5f);
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    BodyInit& init = bodies[n];
    init.body = build_body(test::tet_grid(12 - 2 * static_cast<int>(n), 10, 8, 0.1,
                                          {1.5 * static_cast<double>(n), 0.0, 0.0}),
                           {.stiffness = 5.0e4});
    for (std::size_t s = 1; s < init.body.springs.size(); s += 2)
      std::swap(init.body.springs[s].a, init.body.springs[s].b);
    for (auto& p : init.body.positions)
      p += glm::vec4(jitter(rng), jitter(rng), jitter(rng), 0.0f);
    for (auto& v : init.body.velocities)
      v = glm::vec4(speed(rng), speed(rng), speed(rng), 0.0f);
    init.damping = n == 0 ? 1e-3f : 4e-4f;
  }
  bodies[0].volume_stiffness = 2.0e4f;
  bodies[0].fixed = {0, 1, 2};
  bodies[1].carry_velocity = {-0.3f, 0.1f, 0.0f};
  return assemble_simulation(bodies);
}

TEST(CpuMassSpring, EdgeListsHoldEachDistinctSpringOnceWithTheSignOfTheNodesEnd) {
  const SimulationState w = two_shaken_bodies();
  const sim::SpringEdges edges = sim::build_spring_edges(w);
  EXPECT_LT(3 * edges.size(), w.springs.size()) << "shared tetrahedron edges merge";
  for (std::size_t e = 0; e < edges.size(); ++e) {
    EXPECT_LT(edges.a[e], edges.b[e]);
    if (e > 0) {
      EXPECT_TRUE(edges.a[e - 1] < edges.a[e] ||
                  (edges.a[e - 1] == edges.a[e] && edges.b[e - 1] <= edges.b[e]));
    }
  }
  ASSERT_EQ(edges.node_terms.size(), w.node_spring_list.size());
  ASSERT_EQ(edges.node_offset, w.node_spring_offset);
  for (std::size_t i = 0; i < w.node_count(); ++i) {
    for (std::uint32_t k = w.node_spring_offset[i]; k < w.node_spring_offset[i + 1]; ++k) {
      const std::int32_t tag = w.node_spring_list[k];
      const gpu::Spring& s = w.springs[static_cast<std::size_t>(tag > 0 ? tag : -tag) - 1];
      const sim::EdgeTerm term = edges.node_terms[k];
      EXPECT_EQ(std::min(s.a, s.b), edges.a[term.edge]);
      EXPECT_EQ(std::max(s.a, s.b), edges.b[term.edge]);
      EXPECT_EQ(s.rest_length, edges.rest_length[term.edge]);
      EXPECT_EQ(std::abs(term.signed_stiffness), s.stiffness);
      EXPECT_EQ(term.signed_stiffness > 0.0f, i == edges.a[term.edge]) << "node " << i;
    }
  }
}

TEST(CpuMassSpring, TetCornersSkipZeroStiffnessAndListEachNodesCornersInOrder) {
  const SimulationState w = two_shaken_bodies();
  const sim::TetCorners corners = sim::build_tet_corners(w);
  const std::size_t stiff = w.objects[0].tet_count;  // body 1 has no volume stiffness
  ASSERT_EQ(corners.tets.size(), stiff);
  ASSERT_EQ(corners.corner_slot.size(), 4 * stiff);
  EXPECT_EQ(corners.slot_count, 4 * stiff);
  std::vector<std::uint32_t> seen(corners.slot_count, 0);
  for (std::size_t t = 0; t < stiff; ++t) {
    const std::uint32_t nodes[4] = {corners.tets[t].a, corners.tets[t].b, corners.tets[t].c,
                                    corners.tets[t].d};
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t slot = corners.corner_slot[4 * t + k];
      ASSERT_LT(slot, corners.slot_count);
      ++seen[slot];
      EXPECT_GE(slot, corners.node_offset[nodes[k]]);
      EXPECT_LT(slot, corners.node_offset[nodes[k] + 1]);
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1u), static_cast<std::ptrdiff_t>(seen.size()));
}

// The backend's layout (each edge once, node-major corner slots, fused passes) changes no bit of
// the result against the per-spring passes, on any thread count.
TEST(CpuMassSpring, StepEqualsThePerSpringPassesBitForBit) {
  SimulationState reference = two_shaken_bodies();
  ASSERT_GT(reference.tets.size(), 2 * cpu::kDefaultGrain);  // nodes: 2,376
  const sim::SubstepConstants c{1e-3f, glm::vec3(0.0f, -9.81f, 0.0f), 0.999f};
  for (int threads : {1, 2, 3}) {
    cpu::CpuSimulation sim(threads);
    sim.upload(reference);
    SimulationState expected = reference;
    for (int step = 0; step < 50; ++step) {
      sim.substep(c);
      reference_substep(expected, c);
    }
    const auto same = [](const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& y) {
      return x.size() == y.size() &&
             std::memcmp(x.data(), y.data(), x.size() * sizeof(glm::vec4)) == 0;
    };
    EXPECT_TRUE(same(sim.state().positions, expected.positions)) << threads << " threads";
    EXPECT_TRUE(same(sim.state().velocities, expected.velocities)) << threads << " threads";
    EXPECT_TRUE(same(sim.state().forces, expected.forces)) << threads << " threads";
    EXPECT_FALSE(same(expected.positions, reference.positions));
  }
}

// Three bodies: a fixed one (every node fixed, no path; given velocities, which its first
// substep zeroes, so that it freezes after its second), a free one, and one that sleeps (every
// inverse mass 0) from substep 20 to 40. The step skips the fixed and the sleeping body once they
// have been stepped still (frozen bodies, core/sim/frozen_bodies.h), and every position, velocity
// and force stays the per-spring passes' bit for bit, which step every body always; on 1 and 2
// threads.
TEST(CpuMassSpring, FrozenBodiesAreSkippedAndChangeNoBit) {
  const SimulationState start = test::three_bodies_one_fixed();
  const gpu::ObjectInfo sleeper = start.objects[2];
  const std::vector<float> masses = test::inverse_masses(start, 2), none(masses.size(), 0.0f);
  const sim::SubstepConstants c{1e-3f, glm::vec3(0.0f, -9.81f, 0.0f), 0.999f};
  const auto same = [](const std::vector<glm::vec4>& x, const std::vector<glm::vec4>& y) {
    return x.size() == y.size() &&
           std::memcmp(x.data(), y.data(), x.size() * sizeof(glm::vec4)) == 0;
  };
  for (int threads : {1, 2}) {
    cpu::CpuSimulation sim(threads);
    sim.upload(start);
    SimulationState expected = start;
    const auto set_masses = [&](const std::vector<float>& w) {
      sim.set_inverse_masses(sleeper.node_offset, w);
      for (std::uint32_t k = 0; k < sleeper.node_count; ++k) {
        expected.positions[sleeper.node_offset + k].w = w[k];
        expected.velocities[sleeper.node_offset + k] = glm::vec4(0.0f);
      }
    };
    EXPECT_FALSE(sim.frozen_bodies().frozen(0)) << "not before its first substep";
    for (int step = 0; step < 60; ++step) {
      if (step == 20) set_masses(none);
      if (step == 40) set_masses(masses);
      sim.substep(c);
      reference_substep(expected, c);
      ASSERT_TRUE(same(sim.state().positions, expected.positions)) << "substep " << step;
      ASSERT_TRUE(same(sim.state().velocities, expected.velocities)) << "substep " << step;
      ASSERT_TRUE(same(sim.state().forces, expected.forces)) << "substep " << step;
      EXPECT_EQ(sim.frozen_bodies().frozen(0), step >= 1) << "substep " << step;
      EXPECT_FALSE(sim.frozen_bodies().frozen(1)) << "substep " << step;
      EXPECT_EQ(sim.frozen_bodies().frozen(2), step >= 20 && step < 40) << "substep " << step;
    }
    EXPECT_FALSE(same(sim.state().positions, start.positions));
  }
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
