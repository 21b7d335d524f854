// The GL mass-spring step against the CPU reference (src/cpu), and its own invariants: fixed
// nodes, carry velocity, determinism.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "cpu/cpu_simulation.h"
#include "deformcd/body.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/simulation_state.h"
#include "gl/gl_test_context.h"
#include "gl/sim_test_worlds.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

using test::tet_grid;

// Two bodies of different stiffness (Pa) and damping (s): A (5 x 4 x 4 cubes, one bottom edge of
// nodes fixed) with every node randomly displaced so that its springs are stretched and compressed;
// B (3 x 3 x 3 cubes) squashed to 80 % along y, with a carry velocity and an initial spin.
SimulationState two_body_world() {
  BodyInit a;
  a.body = build_body(tet_grid(5, 4, 4, 0.1), {.stiffness = 1.5e5}, "grid A");
  a.damping = 1e-3f;
  a.name = "A";
  for (std::uint32_t i = 0; i < a.body.positions.size(); ++i) {
    glm::vec4& p = a.body.positions[i];
    if (p.y == 0.0f && p.z == 0.0f) {
      a.fixed.push_back(i);
      continue;
    }
    p += 0.02f * glm::vec4(test::hash_unit(i, 1), test::hash_unit(i, 2), test::hash_unit(i, 3), 0);
  }

  BodyInit b;
  b.body = build_body(tet_grid(3, 3, 3, 0.12, {1.0, 0.0, 0.0}), {.stiffness = 4e4}, "grid B");
  b.damping = 3e-3f;
  b.carry_velocity = {-0.5f, 0.1f, 0.0f};
  b.name = "B";
  const glm::vec3 centre(1.18f, 0.18f, 0.18f);
  for (std::size_t i = 0; i < b.body.positions.size(); ++i) {
    glm::vec4& p = b.body.positions[i];
    const glm::vec3 r = glm::vec3(p) - centre;
    p.y = centre.y + 0.8f * r.y;
    b.body.velocities[i] = glm::vec4(glm::cross(glm::vec3(0.0f, 0.0f, 2.0f), r), 0.0f);
  }
  return assemble_simulation({a, b});
}

class GlSimulationTest : public test_support::GlTest {};

TEST_F(GlSimulationTest, NameAndDeviceDescribeTheContext) {
  GlSimulation gl(context());
  EXPECT_EQ(gl.name(), "gl");
  const DeviceInfo info = query_device_info(context());
  EXPECT_NE(gl.device().find(info.renderer), std::string::npos) << gl.device();
  EXPECT_NE(gl.device().find(info.gl_version), std::string::npos) << gl.device();
  EXPECT_NE(gl.device().find(info.platform), std::string::npos) << gl.device();
}

// One substep computes the same node forces as the CPU, bit for bit: the shaders do the CPU's
// float operations in its order, products and sums `precise` (no fused multiply-add), and
// llvmpipe rounds division and square root correctly, as the CPU does. (A GPU whose division or
// square root is off by an ulp would differ by rounding.)
TEST_F(GlSimulationTest, NodeForcesOfOneSubstepMatchTheCpu) {
  const SimulationState world = two_body_world();
  const sim::SubstepConstants c = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}, 0.5f);
  cpu::CpuSimulation cpu;
  GlSimulation gl(context());
  cpu.upload(world);
  gl.upload(world);
  cpu.substep(c);
  gl.substep(c);

  std::vector<glm::vec4> gl_forces;
  gl.download_node_forces(gl_forces);
  const std::vector<glm::vec4>& cpu_forces = cpu.state().forces;
  ASSERT_EQ(gl_forces.size(), cpu_forces.size());
  ASSERT_GT(test::max_length(cpu_forces), 1.0f) << "the perturbation should stretch springs";
  EXPECT_EQ(gl_forces, cpu_forces);
}

TEST_F(GlSimulationTest, TwoHundredSubstepsAgreeWithTheCpu) {
  const SimulationState world = two_body_world();
  const sim::SubstepConstants c = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}, 0.5f);
  cpu::CpuSimulation cpu;
  GlSimulation gl(context());
  cpu.upload(world);
  gl.upload(world);
  test::run_substeps(cpu, c, 200);
  test::run_substeps(gl, c, 200);

  std::vector<glm::vec4> cpu_x, gl_x, cpu_v, gl_v;
  cpu.download_positions(cpu_x);
  gl.download_positions(gl_x);
  cpu.download_velocities(cpu_v);
  gl.download_velocities(gl_v);
  ASSERT_EQ(gl_x.size(), world.node_count());
  ASSERT_EQ(gl_v.size(), world.node_count());
  // The bodies did move: the comparison is not between two copies of the initial state.
  ASSERT_GT(test::max_distance(cpu_x, world.positions), 0.05f);
  // Bit for bit, as each substep's forces are (above).
  EXPECT_EQ(gl_x, cpu_x);
  EXPECT_EQ(gl_v, cpu_v);
  for (std::size_t i = 0; i < gl_x.size(); ++i) {
    ASSERT_EQ(gl_x[i].w, world.positions[i].w) << "node " << i << ": inverse mass changed";
  }
}

// Frozen bodies (core/sim/frozen_bodies.h): the shaders skip a fixed body and a sleeping one
// element by element, the CPU batch by batch; both freeze and thaw the same bodies at the same
// substeps and end bit for bit equal (the CPU equals the per-spring passes: test_cpu).
TEST_F(GlSimulationTest, FrozenBodiesFreezeAndThawAsOnTheCpu) {
  const SimulationState world = test::three_bodies_one_fixed();
  const gpu::ObjectInfo sleeper = world.objects[2];
  const std::vector<float> masses = test::inverse_masses(world, 2), none(masses.size(), 0.0f);
  const sim::SubstepConstants c = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}, 0.999f);
  cpu::CpuSimulation cpu;
  GlSimulation gl(context());
  cpu.upload(world);
  gl.upload(world);
  for (int step = 0; step < 60; ++step) {
    for (sim::SimulationBackend* backend :
         {static_cast<sim::SimulationBackend*>(&cpu), static_cast<sim::SimulationBackend*>(&gl)}) {
      if (step == 20) backend->set_inverse_masses(sleeper.node_offset, none);
      if (step == 40) backend->set_inverse_masses(sleeper.node_offset, masses);
      backend->substep(c);
    }
    ASSERT_EQ(gl.frozen_bodies().frozen(), cpu.frozen_bodies().frozen()) << "substep " << step;
  }
  EXPECT_TRUE(cpu.frozen_bodies().frozen(0));
  std::vector<glm::vec4> cpu_x, gl_x, cpu_v, gl_v, gl_f;
  cpu.download_positions(cpu_x);
  gl.download_positions(gl_x);
  cpu.download_velocities(cpu_v);
  gl.download_velocities(gl_v);
  gl.download_node_forces(gl_f);
  ASSERT_GT(test::max_distance(cpu_x, world.positions), 0.01f);
  EXPECT_EQ(gl_x, cpu_x);
  EXPECT_EQ(gl_v, cpu_v);
  EXPECT_EQ(gl_f, cpu.state().forces);
}

// The per-node gather has a fixed summation order, so two runs are bit-identical.
TEST_F(GlSimulationTest, RunsAreBitIdentical) {
  const SimulationState world = two_body_world();
  const sim::SubstepConstants c = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f});
  std::vector<glm::vec4> first, second;
  for (std::vector<glm::vec4>* out : {&first, &second}) {
    GlSimulation gl(context());
    gl.upload(world);
    test::run_substeps(gl, c, 50);
    gl.download_positions(*out);
  }
  EXPECT_EQ(first, second);
}

// A body hanging from its top layer: the fixed nodes keep zero velocity and move only with the
// carry velocity, while gravity pulls the free ones down.
TEST_F(GlSimulationTest, FixedNodesMoveOnlyWithTheCarryVelocity) {
  BodyInit init;
  init.body = build_body(tet_grid(3, 3, 3, 0.1));
  init.carry_velocity = {0.3f, 0.0f, -0.2f};
  for (std::uint32_t i = 0; i < init.body.positions.size(); ++i) {
    if (init.body.positions[i].y > 0.29f) init.fixed.push_back(i);
  }
  const SimulationState world = assemble_simulation({init});
  const float h = 1e-3f;
  const int substeps = 100;
  GlSimulation gl(context());
  gl.upload(world);
  test::run_substeps(gl, test::substep_constants(h, {0.0f, -9.81f, 0.0f}), substeps);

  std::vector<glm::vec4> x, v;
  gl.download_positions(x);
  gl.download_velocities(v);
  const glm::vec3 carried = static_cast<float>(substeps) * h * init.carry_velocity;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const glm::vec3 start(world.positions[i]);
    if (world.positions[i].w == 0.0f) {
      EXPECT_LT(glm::distance(glm::vec3(x[i]), start + carried), 1e-5f) << "fixed node " << i;
      EXPECT_EQ(glm::vec3(v[i]), glm::vec3(0.0f)) << "fixed node " << i;
    } else if (start.y == 0.0f) {
      EXPECT_LT(x[i].y, start.y + carried.y - 1e-4f) << "bottom node " << i << " did not sag";
    }
  }
}

// A free body at rest without gravity, carried: every node moves by v t, so the centroid does
// and no spring is stretched; the nodes' own velocities stay (nearly) zero.
TEST_F(GlSimulationTest, CarryVelocityTranslatesAFreeBodyRigidly) {
  BodyInit init;
  init.body = build_body(tet_grid(3, 2, 2, 0.1, {0.2, 0.4, -0.1}));
  init.carry_velocity = {0.5f, -0.2f, 0.1f};
  const SimulationState world = assemble_simulation({init});
  const float h = 1.0f / 240.0f;
  const int substeps = 120;
  GlSimulation gl(context());
  gl.upload(world);
  test::run_substeps(gl, test::substep_constants(h), substeps);

  std::vector<glm::vec4> x, v;
  gl.download_positions(x);
  gl.download_velocities(v);
  const glm::vec3 moved = static_cast<float>(substeps) * h * init.carry_velocity;
  glm::vec3 centroid_start(0.0f), centroid_end(0.0f);
  for (std::size_t i = 0; i < x.size(); ++i) {
    centroid_start += glm::vec3(world.positions[i]);
    centroid_end += glm::vec3(x[i]);
    EXPECT_LT(glm::distance(glm::vec3(x[i]), glm::vec3(world.positions[i]) + moved), 1e-5f)
        << "node " << i;
  }
  const float n = static_cast<float>(x.size());
  EXPECT_LT(glm::distance(centroid_end / n - centroid_start / n, moved), 1e-5f);
  for (const gpu::Spring& s : world.springs) {
    EXPECT_NEAR(glm::distance(glm::vec3(x[s.a]), glm::vec3(x[s.b])), s.rest_length, 1e-5f);
  }
  EXPECT_LT(test::max_length(v), 1e-4f);
}

}  // namespace
}  // namespace deformcd::gl
