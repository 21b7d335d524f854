// The GL contact response (src/gpu/gl/gl_contact_response.h) against the CPU one
// (src/cpu/cpu_contact_response.h): the shaders mirror src/core/response/contact_constraints.h
// line for line with `precise` arithmetic and gather in the same list order, so positions and
// velocities are compared bit for bit after every projection, on hand-made constraints that
// reach every branch, on random dense ones, and inside a running simulation. Also: what an
// empty frame does (only the motion clamp), determinism, and the checked errors.

#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/response/contact_constraints.h"
#include "cpu/cpu_contact_response.h"
#include "cpu/cpu_simulation.h"
#include "cpu/executor.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "gl/contact_test_worlds.h"
#include "gl/gl_test_context.h"
#include "gl/sim_test_worlds.h"
#include "gpu/gl/contact_upload_checks.h"
#include "gpu/gl/gl_contact_response.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

using response::ContactConstants;
using response::FrameConstraints;

// Two constant sets: no restitution and a small untangling step, then restitution, stronger
// friction and a smaller step; a substep of 1 ms.
constexpr ContactConstants kPlain{1e-3f, 0.5f, 0.3f, 0.0f, 0.005f, 1e-3f};
constexpr ContactConstants kBouncy{1e-3f, 0.8f, 0.6f, 0.5f, 0.002f, 4e-3f};
const std::vector<ContactConstants> kSchedule = {kPlain, kPlain, kPlain, kBouncy, kBouncy, kBouncy};
// Sweeps per projection: the schedule's projections cycle through these (one, a
// few, and the default), every other test runs kIterations.
constexpr int kScheduleIterations[3] = {1, 3, 8};
constexpr int kIterations = 4;

// GL and CPU side by side on one world: the GL response corrects a GlSimulation's buffers, the
// CPU one a CpuSimulation's state.
struct SideBySide {
  SideBySide(Context& context, const SimulationState& world)
      : simulation(context),
        gl(context, simulation),
        cpu_simulation(2),
        cpu(cpu_simulation, std::make_shared<cpu::Executor>(2)) {
    simulation.upload(world);
    cpu_simulation.upload(world);
  }
  // What the CPU response corrects in place.
  [[nodiscard]] const SimulationState& cpu_state() const { return cpu_simulation.state(); }

  void begin_frame(const FrameConstraints& c) {
    gl.begin_frame(c);
    cpu.begin_frame(c);
  }
  // Both project; their stray flags must agree too.
  void project(const ContactConstants& k, int iterations) {
    const bool gl_strayed = gl.project(k, iterations);
    const bool cpu_strayed = cpu.project(k, iterations);
    EXPECT_EQ(gl_strayed, cpu_strayed) << "stray flags";
    EXPECT_EQ(gl.last_iterations(), cpu.last_iterations()) << "iterations run";
    if (cpu.last_iterations() > iterations) ++extended;
  }
  // Expects GL's positions and velocities to equal the CPU's bit for bit.
  void expect_equal(const std::string& where) {
    std::vector<glm::vec4> x, v;
    simulation.download_positions(x);
    simulation.download_velocities(v);
    const SimulationState& c = cpu_state();
    EXPECT_EQ(test::bitwise_differences(x, c.positions), 0u)
        << where << ": positions differ by up to " << test::max_distance(x, c.positions) << " m";
    EXPECT_EQ(test::bitwise_differences(v, c.velocities), 0u)
        << where << ": velocities differ by up to " << test::max_distance(v, c.velocities)
        << " m/s";
  }

  GlSimulation simulation;
  GlContactResponse gl;
  cpu::CpuSimulation cpu_simulation;
  cpu::CpuContactResponse cpu;
  int extended = 0;  // projections that ran more iterations than asked (contact_violated)
};

// Runs the schedule on both backends, comparing after every projection; returns how many
// projections ran more iterations than asked.
int expect_agreement(Context& context, const SimulationState& world, const FrameConstraints& c,
                     const std::string& where) {
  SideBySide both(context, world);
  both.begin_frame(c);
  for (std::size_t s = 0; s < kSchedule.size(); ++s) {
    both.project(kSchedule[s], kScheduleIterations[s % 3]);
    both.expect_equal(where + ", projection " + std::to_string(s + 1));
  }
  // Not a comparison of two untouched copies: a good share of the nodes were moved.
  std::size_t moved = 0;
  for (std::size_t i = 0; i < world.node_count(); ++i)
    moved += both.cpu_state().positions[i] != world.positions[i] ? 1 : 0;
  EXPECT_GT(moved, world.node_count() / 4) << where << ": nodes moved by the response";
  return both.extended;
}

class GlContactResponseTest : public test_support::GlTest {};

TEST_F(GlContactResponseTest, HandMadeCasesEqualTheCpuBitForBit) {
  const test::HandMadeContacts set = test::hand_made_contacts();
  expect_agreement(context(), set.world, set.constraints, "hand-made");

  // The set reaches what each scenario names: on the CPU reference after one projection, the
  // nodes of a scenario moved exactly when they should.
  cpu::CpuSimulation simulation(1);
  simulation.upload(set.world);
  const SimulationState& state = simulation.state();  // the response corrects it in place
  cpu::CpuContactResponse cpu(simulation, std::make_shared<cpu::Executor>(1));
  cpu.begin_frame(set.constraints);
  EXPECT_TRUE(cpu.project(kPlain, kIterations))
      << "the push beyond body 1's reach should need a new search";
  for (const test::ContactScenario& s : set.scenarios) {
    bool moved = false;
    for (std::uint32_t i = s.first_node; i < s.first_node + s.node_count; ++i)
      moved = moved || state.positions[i] != set.world.positions[i];
    EXPECT_EQ(moved, s.moves) << s.name;
  }
}

// Within a window the constraints are replaced (update_frame, as a widened search does: some
// pairs gone, others new, the reaches raised): the window's starts stay, the reaches change,
// and GL still equals the CPU bit for bit.
TEST_F(GlContactResponseTest, ConstraintsReplacedWithinAWindowEqualTheCpuBitForBit) {
  const test::RandomContacts set = test::random_contacts(5, 300, 1500);
  const test::RandomContacts other = test::random_contacts(6, 300, 1500);
  SideBySide both(context(), set.world);
  both.begin_frame(set.constraints);
  for (std::size_t s = 0; s < 3; ++s) {
    both.project(kSchedule[s], kScheduleIterations[s]);
    both.expect_equal("before the update, projection " + std::to_string(s + 1));
  }
  const std::vector<glm::vec4> starts = both.gl.download_frame_start();
  // Every third pair dropped, the other set's first 200 added, every reach doubled.
  FrameConstraints replaced = set.constraints;
  replaced.pairs.clear();
  for (std::size_t p = 0; p < set.constraints.pairs.size(); ++p)
    if (p % 3 != 0) replaced.pairs.push_back(set.constraints.pairs[p]);
  replaced.pairs.insert(replaced.pairs.end(), other.constraints.pairs.begin(),
                        other.constraints.pairs.begin() + 200);
  for (glm::vec4& m : replaced.node_motion)
    m.w *= 2.0f;
  both.gl.update_frame(replaced);
  both.cpu.update_frame(replaced);
  const std::vector<glm::vec4> kept = both.gl.download_frame_start();
  ASSERT_EQ(kept.size(), starts.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(glm::vec3(kept[i]), glm::vec3(starts[i])) << "node " << i << "'s start moved";
    EXPECT_EQ(kept[i].w, replaced.node_motion[i].w) << "node " << i << "'s reach";
  }
  for (std::size_t s = 3; s < kSchedule.size(); ++s) {
    both.project(kSchedule[s], kScheduleIterations[s % 3]);
    both.expect_equal("after the update, projection " + std::to_string(s + 1));
  }
}

TEST_F(GlContactResponseTest, RandomDenseConstraintSetsEqualTheCpuBitForBit) {
  int extended = 0;
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const test::RandomContacts set = test::random_contacts(seed, 300, 1500);
    extended +=
        expect_agreement(context(), set.world, set.constraints, "seed " + std::to_string(seed));
  }
  // With volume constraints after the contacts (their own group and counts).
  for (std::uint32_t seed : {4u, 5u}) {
    const test::RandomContacts set = test::random_contacts(seed, 300, 1500, 600);
    expect_agreement(context(), set.world, set.constraints,
                     "seed " + std::to_string(seed) + " with volume constraints");
  }
  // Volume constraints alone.
  const test::RandomContacts volumes = test::random_contacts(6, 300, 0, 800);
  expect_agreement(context(), volumes.world, volumes.constraints, "volume constraints alone");
  // Many work groups, most nodes in several constraints.
  const test::RandomContacts large = test::random_contacts(11, 5000, 20000, 5000);
  extended +=
      expect_agreement(context(), large.world, large.constraints, "5000 nodes, 20000 constraints");
  // Constraints of neighbouring nodes: most of them in the sweeps' two halves, which the CPU
  // sweeps on two threads through all their colours (response::SweepOrder), GL colour by colour.
  const test::RandomContacts local = test::random_contacts(12, 3000, 6000, 3000, true);
  extended += expect_agreement(context(), local.world, local.constraints,
                               "3000 nodes, 9000 constraints of neighbours");
  // Dense random contacts leave some deeper than half their thickness after the iterations
  // asked: the extra iterations (contact_violated) run, alike on both.
  EXPECT_GT(extended, 0) << "no projection ran more iterations than asked";
  RecordProperty("extended_projections", extended);
}

// Edges that one substep takes through each other, or turns through parallel
// (EdgesInOneSubstep): the GL response reads the window's start as the CPU does, and takes
// them back alike, bit for bit.
TEST_F(GlContactResponseTest, EdgesThroughEachOtherInASubstepEqualTheCpuBitForBit) {
  const test::RandomContacts set = test::edges_in_one_substep();
  SideBySide both(context(), set.world);
  both.begin_frame(set.constraints);
  const sim::SubstepConstants substep = test::substep_constants(test::kEdgesSubstep);
  both.simulation.substep(substep);
  both.cpu_simulation.substep(substep);
  ContactConstants k = kPlain;
  k.h = test::kEdgesSubstep;
  both.project(k, kIterations);
  both.expect_equal("after the substep");
  // The CPU's own test (cpu_contact_response_test.cpp) checks where the edges end.
  EXPECT_GT(both.cpu_state().positions[0].z + both.cpu_state().positions[1].z, 0.0f)
      << "edge a still through b";
}

// The response between the substeps of a running simulation (two overlapping grids, stepped by
// the GL mass-spring backend): before each projection the CPU takes GL's state, so that only
// the response is compared, and it agrees bit for bit every time.
TEST_F(GlContactResponseTest, InsideASimulationLoopEqualsTheCpuEverySubstep) {
  BodyInit a, b;
  a.body = build_body(test::tet_grid(4, 3, 3, 0.05), {.stiffness = 2e4}, "A");
  b.body = build_body(test::tet_grid(3, 3, 3, 0.05, {0.15, 0.02, 0.02}), {.stiffness = 2e4}, "B");
  b.carry_velocity = {-0.5f, 0.0f, 0.0f};
  const SimulationState world = assemble_simulation({a, b});
  // Random constraints between A's and B's nodes, of every kind.
  FrameConstraints c =
      test::random_contacts(5, static_cast<std::uint32_t>(world.node_count()), 800).constraints;
  c.node_motion = test::node_motion_of_bodies(
      {glm::vec4(0.1f, 0.0f, 0.0f, 0.01f), glm::vec4(-0.1f, 0.0f, 0.0f, 0.004f)}, world.node_body);
  c.window_start = test::window_start_of(world.positions);
  // And every tetrahedron kept at 0.97 x its rest volume: the grids' own, squeezed by the
  // contacts and gravity, so that many act.
  for (const gpu::ContactPair& v : test::volume_constraints(world, 0.97f, 0.01f))
    c.pairs.push_back(v);

  SideBySide both(context(), world);
  const sim::SubstepConstants substep = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f});
  both.begin_frame(c);
  for (int s = 0; s < 12; ++s) {
    // The backends' substeps agree bit for bit (gl_simulation_test.cpp).
    both.simulation.substep(substep);
    both.cpu_simulation.substep(substep);
    both.project(s < 6 ? kPlain : kBouncy, kIterations);
    both.expect_equal("substep " + std::to_string(s + 1));
  }
  std::vector<glm::vec4> x;
  both.simulation.download_positions(x);
  ASSERT_GT(test::max_distance(x, world.positions), 1e-3f) << "the nodes should have moved";
}

// An empty frame leaves every node as the simulation left it, and flags a stray exactly when a
// free node has left its body's reach around the frame start carried by the drift (fixed nodes
// are carried beyond it and never count).
TEST_F(GlContactResponseTest, AnEmptyFrameOnlyWatchesTheReach) {
  std::vector<glm::vec4> x, v;
  std::vector<std::uint32_t> body;
  for (std::uint32_t i = 0; i < 40; ++i) {
    const float inverse_mass = i % 10 == 3 ? 0.0f : 1.0f;
    const auto f = [](std::uint32_t n) { return static_cast<float>(n); };
    x.emplace_back(0.01f * f(i), 0.02f * f(i % 7), -0.01f * f(i % 5), inverse_mass);
    v.emplace_back(test::hash_unit(i, 1), test::hash_unit(i, 2), test::hash_unit(i, 3), 0.0f);
    body.push_back(i % 2);
  }
  SimulationState world = test::free_nodes(x, v, body, 2);
  world.body_params[0].carry_velocity = {0.5f, 0.0f, 0.0f, 0.0f};
  world.body_params[1].carry_velocity = {0.0f, -1.0f, 0.0f, 0.0f};
  FrameConstraints empty;
  // Body 0 drifts with its carry and stays within its reach; body 1 does not.
  empty.node_motion = test::node_motion_of_bodies(
      {glm::vec4(0.5f, 0.0f, 0.0f, 0.02f), glm::vec4(0.0f, 0.0f, 0.0f, 0.004f)}, world.node_body);
  empty.window_start = test::window_start_of(world.positions);

  GlSimulation simulation(context());
  simulation.upload(world);
  GlContactResponse gl(context(), simulation);
  gl.begin_frame(empty);
  const std::vector<glm::vec4> start = gl.download_frame_start();
  ASSERT_EQ(start.size(), world.node_count());
  for (std::size_t i = 0; i < start.size(); ++i) {
    EXPECT_EQ(start[i], glm::vec4(glm::vec3(world.positions[i]), empty.node_motion[i].w))
        << "frame start of node " << i;
  }

  const sim::SubstepConstants substep = test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f});
  int strays = 0;
  for (int s = 0; s < 10; ++s) {
    simulation.substep(substep);
    std::vector<glm::vec4> before_x, before_v, after_x, after_v;
    simulation.download_positions(before_x);
    simulation.download_velocities(before_v);
    ContactConstants k = kPlain;
    k.elapsed = 1e-3f * static_cast<float>(s + 1);
    const bool strayed = gl.project(k, kIterations);
    simulation.download_positions(after_x);
    simulation.download_velocities(after_v);
    EXPECT_EQ(test::bitwise_differences(after_x, before_x), 0u) << "substep " << s + 1;
    EXPECT_EQ(test::bitwise_differences(after_v, before_v), 0u) << "substep " << s + 1;
    bool expected = false;
    for (std::size_t i = 0; i < before_x.size(); ++i) {
      glm::vec4 xi = before_x[i], vi = before_v[i];
      response::apply_correction(xi, vi, glm::vec3(0.0f), glm::vec3(0.0f));
      expected = response::strayed(xi, start[i], empty.node_motion[i], k.elapsed) || expected;
      if (body[i] == 0 && world.positions[i].w > 0.0f) {
        const glm::vec3 centre = glm::vec3(start[i]) + 0.5f * k.elapsed * glm::vec3(1, 0, 0);
        EXPECT_LE(glm::distance(glm::vec3(before_x[i]), centre), 0.02f) << "node " << i;
      }
    }
    EXPECT_EQ(strayed, expected) << "substep " << s + 1;
    strays += strayed ? 1 : 0;
  }
  EXPECT_GT(strays, 0) << "body 1 should have left its reach";
}

// The per-node gathers have a fixed order, so the result does not depend on how invocations
// are scheduled: two runs are identical, and so is a response reused over frames of other
// sizes (its buffers grown and kept) with a fresh one.
TEST_F(GlContactResponseTest, ResultsDoNotDependOnTheScheduleOrOnEarlierFrames) {
  const test::RandomContacts set = test::random_contacts(7, 400, 3000);
  std::vector<glm::vec4> runs[2];
  for (std::vector<glm::vec4>& out : runs) {
    GlSimulation simulation(context());
    simulation.upload(set.world);
    GlContactResponse gl(context(), simulation);
    gl.begin_frame(set.constraints);
    for (const ContactConstants& k : kSchedule)
      (void)gl.project(k, kIterations);
    simulation.download_positions(out);
  }
  EXPECT_EQ(test::bitwise_differences(runs[0], runs[1]), 0u);
  EXPECT_GT(test::max_distance(runs[0], set.world.positions), 1e-3f);

  // One response through frames of 10, 3000, 0 and again 3000 constraints.
  GlSimulation simulation(context());
  simulation.upload(set.world);
  GlContactResponse reused(context(), simulation);
  FrameConstraints few = test::random_contacts(8, 400, 10).constraints;
  FrameConstraints none;
  none.node_motion = set.constraints.node_motion;
  none.window_start = set.constraints.window_start;
  for (const FrameConstraints* frame :
       std::initializer_list<const FrameConstraints*>{&few, &set.constraints, &none}) {
    reused.begin_frame(*frame);
    (void)reused.project(kPlain, kIterations);
  }
  simulation.upload(set.world);
  reused.begin_frame(set.constraints);
  for (const ContactConstants& k : kSchedule)
    (void)reused.project(k, kIterations);
  std::vector<glm::vec4> reused_x;
  simulation.download_positions(reused_x);
  EXPECT_EQ(test::bitwise_differences(reused_x, runs[0]), 0u);
}

TEST_F(GlContactResponseTest, ProjectNeedsAFrameOfTheCurrentUpload) {
  const test::RandomContacts set = test::random_contacts(3, 50, 40);
  GlSimulation simulation(context());
  GlContactResponse gl(context(), simulation);
  EXPECT_THROW(gl.begin_frame(set.constraints), Error) << "before the simulation's upload";
  simulation.upload(set.world);
  EXPECT_THROW((void)gl.project(kPlain, kIterations), Error) << "before begin_frame";
  gl.begin_frame(set.constraints);
  (void)gl.project(kPlain, kIterations);
  simulation.upload(set.world);  // new buffers: the frame starts no longer apply
  EXPECT_THROW((void)gl.project(kPlain, kIterations), Error);
  gl.begin_frame(set.constraints);
  EXPECT_NO_THROW((void)gl.project(kPlain, kIterations));
}

// Constraints that do not fit are refused before anything changes: the previous frame is kept,
// and projecting it gives what it gave without the refused call.
TEST_F(GlContactResponseTest, RefusedConstraintsKeepThePreviousFrame) {
  const test::RandomContacts set = test::random_contacts(4, 60, 100);
  FrameConstraints bad_node = test::random_contacts(9, 60, 200).constraints;
  bad_node.pairs[150].nodes[2] = 60;
  FrameConstraints bad_motion = test::random_contacts(9, 60, 200).constraints;
  bad_motion.node_motion.resize(2);
  FrameConstraints bad_start = test::random_contacts(9, 60, 200).constraints;
  bad_start.window_start.resize(59);
  std::vector<glm::vec4> results[2];
  for (int refused = 0; refused < 2; ++refused) {
    GlSimulation simulation(context());
    simulation.upload(set.world);
    GlContactResponse gl(context(), simulation);
    gl.begin_frame(set.constraints);
    if (refused == 1) {
      EXPECT_THROW(gl.begin_frame(bad_node), Error);
      EXPECT_THROW(gl.begin_frame(bad_motion), Error);
      EXPECT_THROW(gl.begin_frame(bad_start), Error);
    }
    for (const ContactConstants& k : kSchedule)
      (void)gl.project(k, kIterations);
    simulation.download_positions(results[refused]);
  }
  EXPECT_EQ(test::bitwise_differences(results[0], results[1]), 0u);
}

TEST_F(GlContactResponseTest, BuffersBeyondTheLimitAreRefusedByName) {
  const test::RandomContacts set = test::random_contacts(4, 60, 100);
  GlSimulation simulation(context());
  simulation.upload(set.world);
  // 100 constraints: 3,200 bytes of pairs and 4,800 of impulses; the per-node buffers fit.
  GlContactResponse gl(context(), simulation, {.max_buffer_bytes = 3000});
  try {
    gl.begin_frame(set.constraints);
    FAIL() << "expected a GlError";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("Contact Pair (SSBO 29)"), std::string::npos) << message;
    EXPECT_NE(message.find("Contact Impulse (SSBO 37)"), std::string::npos) << message;
    EXPECT_NE(message.find("GlContactResponseOptions::max_buffer_bytes"), std::string::npos)
        << message;
    EXPECT_EQ(message.find("Frame Start"), std::string::npos) << message;
  }
}

// The host-side checks, without GL.
TEST(ContactUploadChecks, AcceptFittingConstraintsAndNameWhatDoesNotFit) {
  const test::RandomContacts set = test::random_contacts(2, 30, 20);
  EXPECT_EQ(check_constraints_fit(set.constraints, 30), 20u) << "no volume constraint";
  EXPECT_EQ(check_constraints_fit(test::random_contacts(2, 30, 20, 5).constraints, 30), 20u)
      << "the volume constraints begin after the 20 contacts";
  const auto message = [&](const FrameConstraints& c, std::uint32_t nodes) {
    try {
      check_constraints_fit(c, nodes);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message(set.constraints, 31).find("node_motion has 30 entries for 31 nodes"),
            std::string::npos);
  FrameConstraints short_motion = set.constraints;
  short_motion.node_motion.pop_back();
  EXPECT_NE(message(short_motion, 30).find("node_motion has 29 entries for 30 nodes"),
            std::string::npos);
  FrameConstraints short_start = set.constraints;
  short_start.window_start.pop_back();
  EXPECT_NE(message(short_start, 30).find("window_start has 29 entries for 30 nodes"),
            std::string::npos);
  FrameConstraints c = set.constraints;
  c.pairs[7].kind = 4;
  EXPECT_NE(message(c, 30).find("constraint 7 has kind 4"), std::string::npos);
  c = set.constraints;
  c.pairs[7].kind = gpu::kContactVolume;  // a volume constraint before contacts
  EXPECT_NE(message(c, 30).find("constraint 8 (kind"), std::string::npos);
  EXPECT_NE(message(c, 30).find("follows volume constraint 7"), std::string::npos);
  c = set.constraints;
  c.pairs[5].nodes[1] = 30;
  EXPECT_NE(message(c, 30).find("constraint 5 has node 30, but there are 30 nodes"),
            std::string::npos);
}

}  // namespace
}  // namespace deformcd::gl
