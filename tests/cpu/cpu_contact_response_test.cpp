// The CPU contact response on hand-placed nodes: what its projections do to them (the GL
// backend's agreement with it is tests/gl/gl_contact_response_test.cpp's).

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/response/contact_constraints.h"
#include "core/response/frame_constraints.h"
#include "core/response/sweep_order.h"
#include "cpu/cpu_contact_response.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/error.h"
#include "gl/contact_test_worlds.h"
#include "gl/sim_test_worlds.h"

namespace deformcd {
namespace {

constexpr float kThickness = 0.01f;

gpu::ContactPair constraint(std::uint32_t kind, glm::uvec4 nodes) {
  gpu::ContactPair p{};
  for (int k = 0; k < 4; ++k)
    p.nodes[k] = nodes[k];
  p.kind = kind;
  p.side = kind == gpu::kContactVertexFace ? 1.0f : 0.0f;
  p.thickness = kThickness;
  return p;
}

// An edge from a light node L (inverse mass 100) to a heavy one H (1) falls at 1 m/s onto a
// fixed floor (z = 0), both 0.009 m above it (within the 0.01 m thickness): the edge crosses
// over a fixed edge of the floor a quarter of the way from L (an edge-edge constraint), and H
// lies over a fixed face (a vertex-face constraint). The edge-edge constraint alone stops its
// contact point as a rigid lever would, throwing L up at about a third of the approach while H
// goes on down; once H's own constraint stops H, the lever's push on L is too much, and the
// projection must take it back: both nodes end at rest on the floor, neither thrown off it nor
// still falling.
TEST(CpuContactResponse, ALightNodeIsNotThrownOffWhereItsEdgesHeavyEndIsStopped) {
  const std::vector<glm::vec4> x = {
      {0.0f, 0.02f, 0.009f, 100.0f},  // 0: L
      {0.0f, -0.06f, 0.009f, 1.0f},   // 1: H
      {-0.1f, 0.0f, 0.0f, 0.0f},      // 2, 3: the floor's edge under the edge L H
      {0.1f, 0.0f, 0.0f, 0.0f},       //
      {-0.1f, -0.12f, 0.0f, 0.0f},    // 4, 5, 6: the floor's face under H (normal +z)
      {0.1f, -0.12f, 0.0f, 0.0f},     //
      {0.0f, 0.0f, 0.0f, 0.0f},       //
  };
  std::vector<glm::vec4> v(x.size(), glm::vec4(0.0f));
  v[0].z = v[1].z = -1.0f;
  cpu::CpuSimulation simulation(1);
  simulation.upload(test::free_nodes(x, v, std::vector<std::uint32_t>(x.size(), 0u), 1));
  const SimulationState& state = simulation.state();  // the response corrects it in place
  response::FrameConstraints c;
  c.pairs = {constraint(gpu::kContactEdgeEdge, {0, 1, 2, 3}),
             constraint(gpu::kContactVertexFace, {1, 4, 5, 6})};
  for (gpu::ContactPair& p : c.pairs) {
    p.gap = -INFINITY;  // awake
  }
  c.node_motion.assign(x.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // no stray
  c.window_start = test::window_start_of(x);

  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(1));
  response.begin_frame(c);
  response::ContactConstants k{};
  k.h = 1.0f / 960.0f;
  k.elapsed = k.h;
  EXPECT_FALSE(response.project(k, 8));
  EXPECT_NEAR(state.velocities[0].z, 0.0f, 0.02f) << "L: thrown off, or still falling";
  EXPECT_NEAR(state.velocities[1].z, 0.0f, 0.02f) << "H";
  // Moved back by the approach cancelled (1 m/s x h, about 1 mm), to the thickness or above.
  EXPECT_GT(state.positions[0].z, 0.009f);
  EXPECT_GT(state.positions[1].z, 0.009f);
}

// Edges that one substep takes through each other (EdgesInOneSubstep, one projection after the
// substep): within the hold depth, the constraint takes edge a back above b (with the closest
// points' difference as the normal, it pushed a on down, holding the edges crossed); deeper
// than the hold depth it leaves them (a tunnel, the untangling constraints' case); an edge whose
// direction turned through the other's, still 4 mm above it, is pushed up as any edge within
// its thickness, not down through the other (its side turned, its closest points' difference
// did not).
TEST(CpuContactResponse, EdgesThatWentThroughEachOtherInASubstepAreTakenBack) {
  const test::RandomContacts set = test::edges_in_one_substep();
  cpu::CpuSimulation simulation(1);
  simulation.upload(set.world);
  const SimulationState& state = simulation.state();
  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(1));
  response.begin_frame(set.constraints);
  simulation.substep(test::substep_constants(test::kEdgesSubstep));
  // Where the substep left edge a's middle, above b's (z = 0).
  const auto a_height = [&](test::EdgesInOneSubstep kind) {
    const std::uint32_t first = 4u * static_cast<std::uint32_t>(kind);
    return 0.5f * (state.positions[first].z + state.positions[first + 1u].z);
  };
  EXPECT_NEAR(a_height(test::EdgesInOneSubstep::kThrough), -0.002f, 1e-6f);
  EXPECT_NEAR(a_height(test::EdgesInOneSubstep::kThroughDeep), -0.026f, 1e-6f);
  EXPECT_NEAR(a_height(test::EdgesInOneSubstep::kTurnedParallel), 0.004f, 1e-6f);
  response::ContactConstants k{};
  k.h = test::kEdgesSubstep;
  k.elapsed = k.h;
  (void)response.project(k, 8);
  EXPECT_GT(a_height(test::EdgesInOneSubstep::kThrough), 0.0f) << "still through b";
  EXPECT_NEAR(a_height(test::EdgesInOneSubstep::kThroughDeep), -0.026f, 1e-6f) << "moved";
  EXPECT_GT(a_height(test::EdgesInOneSubstep::kTurnedParallel), 0.004f) << "pushed toward b";
}

// A tetrahedron's signed volume on the state's positions.
float volume_of(const SimulationState& s, const gpu::ContactPair& p) {
  const glm::vec3 x[4] = {glm::vec3(s.positions[p.nodes[0]]), glm::vec3(s.positions[p.nodes[1]]),
                          glm::vec3(s.positions[p.nodes[2]]), glm::vec3(s.positions[p.nodes[3]])};
  glm::vec3 g[4];
  return sim::tetrahedron_volume(x, g);
}

// The volume constraint of a world's first four nodes, kept at `floor` (m^3), its corners moved
// at most `step_limit` an iteration.
gpu::ContactPair first_tetrahedron_floor(float floor, float step_limit) {
  gpu::ContactPair p{};
  for (std::uint32_t k = 0; k < 4u; ++k)
    p.nodes[k] = k;
  p.kind = gpu::kContactVolume;
  p.thickness = floor;
  p.gap = -INFINITY;
  p.step_limit = step_limit;
  return p;
}

// One projection of `simulation`'s four nodes (at rest in the response's eyes: reach 1 m) with
// `pair` alone, `iterations` asked, a substep of 1 ms, on one thread; the iterations it ran.
int project_one_tetrahedron(cpu::CpuSimulation& simulation, const gpu::ContactPair& pair,
                            int iterations) {
  response::FrameConstraints c;
  c.pairs = {pair};
  c.node_motion.assign(4, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  c.window_start = test::window_start_of(simulation.state().positions);
  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(1));
  response.begin_frame(c);
  response::ContactConstants k{};
  k.h = 1e-3f;
  k.elapsed = k.h;
  (void)response.project(k, iterations);
  return response.last_iterations();
}

// One projection of the volume constraints alone on tetrahedra of a unit corner (rest volume
// 1/6 x 0.01^3) whose apex is pushed toward, or through, the opposite face, each moving toward
// it at 1 m/s: the inverted one and the collapsed one come back to (nearly) the floor, their
// collapse stopped; one above the floor moving the same way is left alone; momentum is kept.
TEST(VolumeConstraint, ACollapsedOrInvertedTetrahedronComesBackToItsFloorWithItsCollapseStopped) {
  constexpr float kEdge = 0.01f;
  constexpr float kRest = kEdge * kEdge * kEdge / 6.0f;
  constexpr float kFloor = 0.3f * kRest;
  // Apex heights over the base, in edges: inverted, collapsed below the floor, above it.
  const float heights[3] = {-0.5f, 0.1f, 0.6f};
  std::vector<glm::vec4> x, v;
  response::FrameConstraints c;
  for (int t = 0; t < 3; ++t) {
    const glm::vec3 o(0.1f * static_cast<float>(t), 0.0f, 0.0f);
    const std::uint32_t first = static_cast<std::uint32_t>(x.size());
    x.emplace_back(o, 1.0f);
    x.emplace_back(o + glm::vec3(kEdge, 0.0f, 0.0f), 2.0f);
    x.emplace_back(o + glm::vec3(0.0f, kEdge, 0.0f), 1.0f);
    x.emplace_back(o + glm::vec3(0.0f, 0.0f, heights[t] * kEdge), 0.5f);  // the apex
    for (int k = 0; k < 3; ++k)
      v.emplace_back(0.0f);
    v.emplace_back(0.0f, 0.0f, -1.0f, 0.0f);
    gpu::ContactPair p{};
    for (std::uint32_t k = 0; k < 4u; ++k)
      p.nodes[k] = first + k;
    p.kind = gpu::kContactVolume;
    p.thickness = kFloor;
    p.gap = -INFINITY;
    p.step_limit = kEdge;
    c.pairs.push_back(p);
  }
  cpu::CpuSimulation simulation(1);
  simulation.upload(test::free_nodes(x, v, std::vector<std::uint32_t>(x.size(), 0u), 1));
  const SimulationState& state = simulation.state();  // the response corrects it in place
  c.node_motion.assign(x.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  c.window_start = test::window_start_of(x);
  ASSERT_LT(volume_of(state, c.pairs[0]), 0.0f) << "the first starts inverted";
  const auto momentum = [&](const std::vector<glm::vec4>& values, int t) {
    glm::dvec3 sum(0.0);
    for (int k = 0; k < 4; ++k)
      sum += glm::dvec3(glm::vec3(values[4 * t + k])) / static_cast<double>(x[4 * t + k].w);
    return sum;
  };
  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(1));
  response.begin_frame(c);
  response::ContactConstants k{};
  k.h = 1e-3f;
  k.elapsed = k.h;
  EXPECT_FALSE(response.project(k, 8));
  for (int t = 0; t < 2; ++t) {
    const float after = volume_of(state, c.pairs[t]);
    EXPECT_GT(after, 0.95f * kFloor) << "tetrahedron " << t;
    EXPECT_LT(after, 1.5f * kFloor) << "tetrahedron " << t << ": pushed past its floor";
    // Its collapse rate (sum of g . v) is stopped, not turned into an expansion.
    glm::vec3 corners[4], g[4];
    for (int i = 0; i < 4; ++i)
      corners[i] = glm::vec3(state.positions[4 * t + i]);
    sim::tetrahedron_volume(corners, g);
    float rate = 0.0f;
    for (int i = 0; i < 4; ++i)
      rate += glm::dot(g[i], glm::vec3(state.velocities[4 * t + i]));
    EXPECT_NEAR(rate, 0.0f, 1e-3f * kEdge * kEdge) << "tetrahedron " << t;
    // Within the rounding of coordinates near 0.2 m (an ulp is 1.5e-8 m).
    EXPECT_LT(glm::length(momentum(state.positions, t) - momentum(x, t)), 1e-7) << t;
    EXPECT_LT(glm::length(momentum(state.velocities, t) - momentum(v, t)), 1e-6) << t;
  }
  for (int n = 8; n < 12; ++n) {
    EXPECT_EQ(state.positions[n], x[n]) << "above its floor: node " << n << " moved";
    EXPECT_EQ(state.velocities[n], v[n]) << "above its floor: node " << n;
  }
}

// A tetrahedron flattened to a line has volume gradients near zero, and 1 / their square would
// throw its corners: no corner moves more than step_limit in one iteration.
TEST(VolumeConstraint, ATetrahedronFlattenedToALineMovesNoCornerMoreThanItsStepLimit) {
  const std::vector<glm::vec4> x = {{0.0f, 0.0f, 0.0f, 1.0f},
                                    {0.01f, 1e-6f, 0.0f, 1.0f},
                                    {0.02f, 0.0f, 1e-6f, 1.0f},
                                    {0.03f, -1e-6f, -1e-6f, 1.0f}};
  const std::vector<glm::vec4> v(4, glm::vec4(0.0f));
  cpu::CpuSimulation simulation(1);
  simulation.upload(test::free_nodes(x, v, {0, 0, 0, 0}, 1));
  const SimulationState& state = simulation.state();  // the response corrects it in place
  const gpu::ContactPair p = first_tetrahedron_floor(1e-7f, 0.002f);
  (void)project_one_tetrahedron(simulation, p, 1);
  float largest = 0.0f;
  for (int i = 0; i < 4; ++i)
    largest = std::max(largest, glm::length(glm::vec3(state.positions[i] - x[i])));
  EXPECT_GT(largest, 0.5f * p.step_limit) << "the constraint should act";
  EXPECT_LE(largest, 1.0001f * p.step_limit);
}

// A tetrahedron turned inside out (its apex two edges through the base) whose corners may move
// only a fifth of an edge an iteration: two iterations asked cannot bring it back. Flagged
// `converge` (as the world flags every volume constraint), the projection iterates on while it
// is below half its floor (contact_violated), up to kMaxIterationFactor x the iterations asked,
// and ends above that; unflagged, it stops after the two, still inverted.
TEST(VolumeConstraint, AnInvertedTetrahedronIsIteratedBackAboveHalfItsFloor) {
  constexpr float kEdge = 0.01f;
  constexpr float kFloor = 0.3f * kEdge * kEdge * kEdge / 6.0f;
  constexpr int kAsked = 2;
  const std::vector<glm::vec4> x = {{0.0f, 0.0f, 0.0f, 1.0f},
                                    {kEdge, 0.0f, 0.0f, 1.0f},
                                    {0.0f, kEdge, 0.0f, 1.0f},
                                    {0.0f, 0.0f, -2.0f * kEdge, 1.0f}};
  const std::vector<glm::vec4> v(4, glm::vec4(0.0f));
  for (const float converge : {1.0f, 0.0f}) {
    SCOPED_TRACE("converge " + std::to_string(converge));
    cpu::CpuSimulation simulation(1);
    simulation.upload(test::free_nodes(x, v, {0, 0, 0, 0}, 1));
    const SimulationState& state = simulation.state();  // the response corrects it in place
    gpu::ContactPair p = first_tetrahedron_floor(kFloor, 0.2f * kEdge);
    p.converge = converge;
    const int iterations = project_one_tetrahedron(simulation, p, kAsked);
    const float after = volume_of(state, p);
    if (converge > 0.0f) {
      EXPECT_GT(iterations, kAsked);
      EXPECT_LE(iterations, response::kMaxIterationFactor * kAsked);
      EXPECT_GE(after, response::kResidualShare * kFloor);
    } else {
      EXPECT_EQ(iterations, kAsked);
      EXPECT_LT(after, 0.0f) << "two limited steps should not bring it back";
    }
  }
}

// A unit-corner tetrahedron (edge kPushEdge; nodes 0-2 its base, 3 its apex, `apex` edges over
// the base point (0.2, 0.2)) under a fixed face 0.2 edges above the apex, facing down (nodes 4-6),
// projected once (8 iterations asked, a 1 ms substep, one thread) with `contact` (the apex
// against the face; awake) and the tetrahedron's volume constraint `floor`: its volume before,
// and the nodes after.
constexpr float kPushEdge = 0.01f;

struct PushedApex {
  float volume_before;
  SimulationState after;
};

PushedApex push_apex(float apex, gpu::ContactPair contact, const gpu::ContactPair& floor) {
  constexpr float kEdge = kPushEdge;
  const float face = apex + 0.2f;
  const std::vector<glm::vec4> x = {
      {0.0f, 0.0f, 0.0f, 1.0f},
      {kEdge, 0.0f, 0.0f, 1.0f},
      {0.0f, kEdge, 0.0f, 1.0f},
      {0.2f * kEdge, 0.2f * kEdge, apex * kEdge, 1.0f},
      {-kEdge, -kEdge, face * kEdge, 0.0f},
      {-kEdge, 2.0f * kEdge, face * kEdge, 0.0f},
      {2.0f * kEdge, -kEdge, face * kEdge, 0.0f},
  };
  const std::vector<glm::vec4> v(x.size(), glm::vec4(0.0f));
  cpu::CpuSimulation simulation(1);
  simulation.upload(test::free_nodes(x, v, std::vector<std::uint32_t>(x.size(), 0u), 1));
  const float before = volume_of(simulation.state(), floor);
  response::FrameConstraints c;
  for (std::uint32_t k = 0; k < 4u; ++k)
    contact.nodes[k] = 3u + k;
  contact.gap = -INFINITY;  // awake
  c.pairs = {contact, floor};
  c.node_motion.assign(x.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));  // no stray
  c.window_start = test::window_start_of(x);
  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(1));
  response.begin_frame(c);
  response::ContactConstants k{};
  k.h = 1e-3f;
  k.elapsed = k.h;
  (void)response.project(k, 8);
  return {before, simulation.state()};
}

// A tetrahedron above its floor (apex at 0.4 of an edge: 0.4 of its rest volume, the floor 0.3
// of it) whose apex a contact within the projection pushes a whole edge down, through the base: a
// fixed face 0.2 edges above the apex, facing down, holds it a thickness of 1 edge below. The
// activity pass fixes the active set before the contact moves anything; the volume constraint
// is in it (watched from kVolumeWatch x its floor) and keeps the tetrahedron at its floor
// instead of letting the contact turn it inside out (as it did when only a tetrahedron already
// below its floor was active).
TEST(VolumeConstraint, ATetrahedronAContactPushesThroughItselfWithinAProjectionKeepsItsFloor) {
  constexpr float kEdge = kPushEdge;
  constexpr float kFloor = 0.3f * kEdge * kEdge * kEdge / 6.0f;
  gpu::ContactPair contact = constraint(gpu::kContactVertexFace, {3, 4, 5, 6});
  contact.thickness = kEdge;
  const gpu::ContactPair floor = first_tetrahedron_floor(kFloor, kEdge);
  const PushedApex pushed = push_apex(0.4f, contact, floor);
  ASSERT_GT(pushed.volume_before, 1.2f * kFloor) << "starts above its floor";
  ASSERT_LT(pushed.volume_before, response::kVolumeWatch * kFloor) << "and watched";
  EXPECT_LT(pushed.after.positions[3].z, 0.2f * kEdge) << "the contact should push the apex down";
  EXPECT_GT(volume_of(pushed.after, floor), 0.9f * kFloor) << "turned inside out by the contact";
}

// The same push on a tetrahedron above the watch (apex at 0.8 of an edge: 2.7x its floor, whose
// watch is 2x): a fixed face 0.2 edges above the apex holds it 1.4 edges below, through the
// base. Where the contact is a self pair the rest-distance rule cut (its hold depth deeper than
// its thickness: response::guards_volumes) and the tetrahedron is marked thin (lower at rest
// than its body's thickness), its volume constraint acts in that projection and keeps its
// floor. An ordinary contact, or a tetrahedron not marked thin, leaves the constraint idle, and
// the push turns the tetrahedron inside out, as it did the armadillo's cap sliver.
TEST(VolumeConstraint, AGuardingContactWatchesTheFloorOfItsCornersThinTetrahedra) {
  constexpr float kEdge = kPushEdge;
  constexpr float kFloor = 0.3f * kEdge * kEdge * kEdge / 6.0f;
  struct Case {
    bool guard;
    bool thin;
  };
  for (const Case test : {Case{true, true}, Case{false, true}, Case{true, false}}) {
    SCOPED_TRACE(std::string(test.guard ? "guarding" : "ordinary") + " contact, " +
                 (test.thin ? "thin" : "thick") + " tetrahedron");
    gpu::ContactPair contact = constraint(gpu::kContactVertexFace, {3, 4, 5, 6});
    contact.thickness = 1.4f * kEdge;
    contact.hold_depth = test.guard ? 2.0f * contact.thickness : 0.0f;
    ASSERT_EQ(response::guards_volumes(contact), test.guard);
    gpu::ContactPair floor = first_tetrahedron_floor(kFloor, kEdge);
    floor.side = test.thin ? 1.0f : 0.0f;
    const PushedApex pushed = push_apex(0.8f, contact, floor);
    ASSERT_GT(pushed.volume_before, response::kVolumeWatch * kFloor) << "starts unwatched";
    EXPECT_LT(pushed.after.positions[3].z, 0.5f * kEdge) << "the contact should push the apex down";
    if (test.guard && test.thin) {
      EXPECT_GT(volume_of(pushed.after, floor), 0.9f * kFloor)
          << "turned inside out by the contact";
    } else {
      EXPECT_LT(volume_of(pushed.after, floor), 0.0f) << "unwatched, the push should invert it";
    }
  }
}

// A thin tetrahedron above the watch (apex at 0.8 of an edge: 2.7x its floor) whose apex falls
// onto the base at 10 m/s would be inside out after the next substep (1 ms: 1 cm): its volume
// constraint watches it (response::volume_watched: below the watch after a substep of its
// collapse) and leaves the collapse that reaches the floor within the substep, no more. One
// falling at 1 m/s stays above the watch over the substep, and no node moves; nor does one not
// marked thin (the motion bound keeps nodes from crossing a thick one within a substep).
TEST(VolumeConstraint, AThinTetrahedronCollapsingPastItsWatchWithinASubstepIsWatched) {
  constexpr float kEdge = 0.01f;
  constexpr float kFloor = 0.3f * kEdge * kEdge * kEdge / 6.0f;
  constexpr float kH = 1e-3f;
  const std::vector<glm::vec4> x = {{0.0f, 0.0f, 0.0f, 1.0f},
                                    {kEdge, 0.0f, 0.0f, 1.0f},
                                    {0.0f, kEdge, 0.0f, 1.0f},
                                    {0.2f * kEdge, 0.2f * kEdge, 0.8f * kEdge, 1.0f}};
  struct Case {
    float fall;  // m/s
    bool thin;
  };
  for (const Case test : {Case{10.0f, true}, Case{1.0f, true}, Case{10.0f, false}}) {
    SCOPED_TRACE("falling at " + std::to_string(test.fall) + " m/s, " +
                 (test.thin ? "thin" : "thick"));
    std::vector<glm::vec4> v(4, glm::vec4(0.0f));
    v[3].z = -test.fall;
    cpu::CpuSimulation simulation(1);
    simulation.upload(test::free_nodes(x, v, {0, 0, 0, 0}, 1));
    const SimulationState& state = simulation.state();  // the response corrects it in place
    gpu::ContactPair p = first_tetrahedron_floor(kFloor, kEdge);
    p.side = test.thin ? 1.0f : 0.0f;
    ASSERT_GT(volume_of(state, p), response::kVolumeWatch * kFloor) << "starts above the watch";
    (void)project_one_tetrahedron(simulation, p, 8);
    // The volume after the next substep, at these velocities (its rate: sum of g_k . v_k).
    glm::vec3 corners[4], g[4];
    for (int i = 0; i < 4; ++i)
      corners[i] = glm::vec3(state.positions[i]);
    const float volume = sim::tetrahedron_volume(corners, g);
    float rate = 0.0f;
    for (int i = 0; i < 4; ++i)
      rate += glm::dot(g[i], glm::vec3(state.velocities[i]));
    const float next = volume + kH * rate;
    if (test.thin && test.fall > 5.0f) {
      EXPECT_GT(next, 0.9f * kFloor) << "its collapse should stop at the floor";
      EXPECT_LT(state.velocities[3].z, -1.0f) << "and not be turned into an expansion";
      RecordProperty("next_over_floor", std::to_string(next / kFloor));
    } else {
      for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(state.positions[i], x[i]) << "node " << i;
        EXPECT_EQ(state.velocities[i], v[i]) << "node " << i;
      }
    }
  }
}

// `set`'s world after three projections of its constraints (8 iterations each, with friction)
// on `threads` threads.
SimulationState after_three_projections(const test::RandomContacts& set, int threads) {
  cpu::CpuSimulation simulation(threads);
  simulation.upload(set.world);
  cpu::CpuContactResponse response(simulation, std::make_shared<cpu::Executor>(threads));
  response.begin_frame(set.constraints);
  response::ContactConstants k{};
  k.h = 1e-3f;
  k.friction_static = 0.5f;
  k.friction_dynamic = 0.4f;
  k.max_untangle_step = 1e-3f;
  for (int s = 1; s <= 3; ++s) {
    k.elapsed = k.h * static_cast<float>(s);
    (void)response.project(k, 8);
  }
  return simulation.state();
}

// The projections of contacts and volume constraints together give the same bits on one and on
// eight threads (each constraint writes its own slots; each node sums its list in order).
TEST(VolumeConstraint, OneAndEightThreadsGiveTheSameBits) {
  const tbb::global_control allow_eight(tbb::global_control::max_allowed_parallelism, 8);
  const test::RandomContacts set = test::random_contacts(21, 2000, 8000, 4000);
  const SimulationState one = after_three_projections(set, 1);
  const SimulationState eight = after_three_projections(set, 8);
  EXPECT_EQ(test::bitwise_differences(one.positions, eight.positions), 0u);
  EXPECT_EQ(test::bitwise_differences(one.velocities, eight.velocities), 0u);
  EXPECT_GT(test::bitwise_differences(one.positions, set.world.positions), 1000u)
      << "the projections should move the nodes";
}

// Constraints of neighbouring nodes, most of them in the sweeps' two halves (which two threads
// sweep at once, each through all its colours): one, two and eight threads give the same bits.
TEST(CpuContactResponse, SweepsByHalvesGiveTheSameBitsOnOneTwoAndEightThreads) {
  const tbb::global_control allow_eight(tbb::global_control::max_allowed_parallelism, 8);
  const test::RandomContacts set = test::random_contacts(22, 3000, 6000, 3000, true);
  {
    // The split holds most of them (all listed here, as if all acted).
    std::vector<std::uint32_t> all(set.constraints.pairs.size());
    for (std::uint32_t p = 0; p < all.size(); ++p)
      all[p] = p;
    response::SweepOrder order;
    order.colour(set.constraints.pairs, all, 6000u, set.constraints.window_start);
    std::uint32_t in_halves = 0;
    for (const response::SweepOrder::Run& run : order.runs())
      if (run.halves) in_halves += order.colour_begin()[run.end] - order.colour_begin()[run.first];
    ASSERT_GT(in_halves, 8000u);
  }
  std::vector<SimulationState> states;
  for (const int threads : {1, 2, 8})
    states.push_back(after_three_projections(set, threads));
  for (std::size_t r = 1; r < states.size(); ++r) {
    EXPECT_EQ(test::bitwise_differences(states[0].positions, states[r].positions), 0u) << r;
    EXPECT_EQ(test::bitwise_differences(states[0].velocities, states[r].velocities), 0u) << r;
  }
  EXPECT_GT(test::bitwise_differences(states[0].positions, set.world.positions), 1000u)
      << "the projections should move the nodes";
}

// The backends solve the volume constraints as the list's last group: one before a contact is
// refused, naming both.
TEST(VolumeConstraint, AVolumeConstraintBeforeAContactIsRefused) {
  std::vector<gpu::ContactPair> pairs(3);
  pairs[1].kind = gpu::kContactVolume;
  pairs[2].kind = gpu::kContactEdgeEdge;
  try {
    (void)response::first_volume_constraint(pairs);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("constraint 2 (kind 1) follows volume constraint 1"),
              std::string::npos)
        << e.what();
  }
  pairs[2].kind = gpu::kContactVolume;
  EXPECT_EQ(response::first_volume_constraint(pairs), 1u);
  pairs.resize(1);
  EXPECT_EQ(response::first_volume_constraint(pairs), 1u);
}

// contact_clear, the activity pass's bound before the geometry, never clears a constraint that
// acts (contact_geometry's C < 0), and clears most of those beyond their thickness: random edge
// pairs and vertex-face pairs at 0.3-3 thicknesses (their relative placements drawn at random,
// some nearly parallel or degenerate), near the origin and 1 km from it.
TEST(ContactConstraints, ClearNeverHidesAnActingConstraint) {
  std::mt19937 random(12345);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  const auto direction = [&] {
    glm::vec3 d(unit(random), unit(random), unit(random));
    return glm::length(d) > 1e-3f ? glm::normalize(d) : glm::vec3(1.0f, 0.0f, 0.0f);
  };
  int acting = 0, beyond = 0, cleared = 0;
  for (int i = 0; i < 200000; ++i) {
    const std::uint32_t kind = i % 2 == 0 ? gpu::kContactEdgeEdge : gpu::kContactVertexFace;
    const glm::vec3 origin = i % 4 < 2 ? glm::vec3(0.0f) : glm::vec3(1000.0f, -700.0f, 300.0f);
    const float edge = 0.05f;  // 5 thicknesses
    const float gap = kThickness * (0.3f + 2.7f * 0.5f * (unit(random) + 1.0f));
    glm::vec3 x[4];
    if (kind == gpu::kContactEdgeEdge) {
      // Edge a through the origin, edge b through a point `gap` away along their common normal
      // (then moved along itself, so the segments need not cross).
      const glm::vec3 da = direction();
      glm::vec3 db = direction();
      if (i % 10 == 0) db = glm::normalize(da + 1e-3f * direction());  // nearly parallel
      glm::vec3 n = glm::cross(da, db);
      n = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
      const float sa = 0.5f * (unit(random) + 1.0f), sb = 0.5f * (unit(random) + 1.0f);
      const glm::vec3 shift = 0.2f * edge * unit(random) * db;
      x[0] = origin - sa * edge * da;
      x[1] = x[0] + edge * da;
      x[2] = origin + gap * n - sb * edge * db + shift;
      x[3] = x[2] + edge * db;
    } else {
      // A face around the origin, the vertex `gap` in front of (or beside) it.
      const glm::vec3 n = direction();
      const glm::vec3 t = glm::normalize(glm::cross(n, direction() + glm::vec3(0.0f, 0.0f, 2.0f)));
      const glm::vec3 b = glm::cross(n, t);
      x[1] = origin + edge * (-0.5f * t - 0.3f * b);
      x[2] = origin + edge * (0.6f * t - 0.2f * b);
      x[3] = origin + edge * (0.1f * t + 0.7f * b);
      if (i % 10 == 1) x[3] = x[2] + 1e-4f * edge * t;  // a sliver
      x[0] = origin + gap * n + 0.4f * edge * (unit(random) * t + unit(random) * b);
    }
    gpu::ContactPair pair = constraint(kind, glm::uvec4(0u, 1u, 2u, 3u));
    glm::vec3 normal(0.0f);
    float weights[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    float c = 0.0f;
    const bool acts = response::contact_geometry(pair, x, x, normal, weights, c) && c < 0.0f;
    const bool clear = response::contact_clear(pair, x);
    ASSERT_FALSE(acts && clear) << "constraint " << i << " (kind " << kind << ", gap " << gap
                                << ") acts (C = " << c << ") but was cleared";
    acting += acts ? 1 : 0;
    if (gap > 1.05f * kThickness) {
      ++beyond;
      cleared += clear ? 1 : 0;
    }
  }
  EXPECT_GT(acting, 10000);  // the test reaches constraints that act
  // The bound is loose only for nearly parallel edges and vertices beside their face.
  EXPECT_GT(cleared, beyond / 2) << cleared << " of " << beyond;
}

// slid_before: none, some or all of a contact's free nodes had a contact slide in the substep
// before (the stamps equal to the projection's count less one); fixed nodes do not count.
TEST(ContactConstraints, SlidBeforeCountsOnlyFreeNodes) {
  const glm::vec4 x[4] = {{0.0f, 0.0f, 0.0f, 1.0f},
                          {0.0f, 0.0f, 0.0f, 2.0f},
                          {0.0f, 0.0f, 0.0f, 0.0f},
                          {0.0f, 0.0f, 0.0f, 0.0f}};
  const std::uint32_t substep = 7u;
  const std::uint32_t all[4] = {6u, 6u, response::kNeverSlid, 3u};
  const std::uint32_t some[4] = {6u, 5u, 6u, 6u};
  const std::uint32_t none[4] = {5u, response::kNeverSlid, 6u, 6u};
  EXPECT_EQ(response::slid_before(x, all, substep), response::kAllSlid);
  EXPECT_EQ(response::slid_before(x, some, substep), response::kSomeSlid);
  EXPECT_EQ(response::slid_before(x, none, substep), response::kNoneSlid);
}

// The hold: a vertex 5 mm deep in the thickness of a fixed face (normal +z) whose projection
// start says pushes carried it `drift` along x since the projection began. One iteration of a
// sticking contact (static 0.5: its push is the 5 mm of depth, so the hold may take back up to
// 2.5 mm) takes the drift back, all of it below 2.5 mm and 2.5 mm of it above; a contact with a
// free node that slid in the last substep holds nothing; and a tangential velocity, which
// moves the node by h x it but leaves its position less h x its velocity as it was, is no
// drift (the velocity friction's, not the hold's).
TEST(ContactConstraints, AStickingContactHoldsItsPointAgainstPushesWithinItsStaticCone) {
  gpu::ContactPair pair = constraint(gpu::kContactVertexFace, glm::uvec4(0u, 1u, 2u, 3u));
  const glm::vec4 x[4] = {{0.01f, 0.01f, 0.005f, 1.0f},
                          {0.0f, 0.0f, 0.0f, 0.0f},
                          {0.05f, 0.0f, 0.0f, 0.0f},
                          {0.0f, 0.05f, 0.0f, 0.0f}};
  const std::uint32_t count[4] = {1u, 1u, 1u, 1u};
  response::ContactConstants k{};
  k.h = 1e-3f;
  k.friction_static = 0.5f;
  k.friction_dynamic = 0.4f;
  // The vertex's x move (its position correction) after one iteration.
  const auto held = [&](float drift, glm::vec3 velocity, std::uint32_t history) {
    const glm::vec4 v[4] = {glm::vec4(velocity, 0.0f), glm::vec4(0.0f), glm::vec4(0.0f),
                            glm::vec4(0.0f)};
    glm::vec4 start[4];
    for (int i = 0; i < 4; ++i)
      start[i] = glm::vec4(glm::vec3(x[i]) - k.h * glm::vec3(v[i]), 0.0f);
    start[0].x -= drift;
    glm::vec4 given[3], correction[8];
    // First iteration, not the last (where a slip may start sliding).
    const glm::vec3 window_start[4] = {glm::vec3(x[0]), glm::vec3(x[1]), glm::vec3(x[2]),
                                       glm::vec3(x[3])};
    response::solve_contact(pair, x, v, count, start, window_start, k, true, false, history, given,
                            correction);
    EXPECT_NEAR(correction[0].z, 0.005f, 1e-6f) << "pushed out of the thickness";
    return correction[0].x;
  };
  EXPECT_NEAR(held(0.001f, glm::vec3(0.0f), response::kNoneSlid), -0.001f, 1e-6f);
  EXPECT_NEAR(held(0.004f, glm::vec3(0.0f), response::kNoneSlid), -0.0025f, 1e-6f);
  EXPECT_EQ(held(0.001f, glm::vec3(0.0f), response::kSomeSlid), 0.0f);
  EXPECT_EQ(held(0.001f, glm::vec3(0.0f), response::kAllSlid), 0.0f);
  // 0.1 m/s along x, no drift: the velocity friction alone (its cone is empty here: the vertex
  // does not approach, so it stops nothing of the slip), no hold.
  EXPECT_EQ(held(0.0f, glm::vec3(0.1f, 0.0f, 0.0f), response::kNoneSlid), 0.0f);
}

// A volume constraint weighs its nodes by their inverse masses alone (the sweep applies it at
// once, and the next constraint sees the move): a tetrahedron flattened at rest, its apex alone
// free, rises the same whatever count of acting constraints its nodes are given.
TEST(VolumeConstraint, IgnoresTheNodesCounts) {
  const gpu::ContactPair pair = first_tetrahedron_floor(1e-7f, 1.0f);
  const glm::vec4 x[4] = {{0.0f, 0.0f, 0.0f, 0.0f},
                          {0.01f, 0.0f, 0.0f, 0.0f},
                          {0.0f, 0.01f, 0.0f, 0.0f},
                          {0.002f, 0.002f, 0.001f, 1.0f}};  // 1/6 x 1e-7 m^3, below the floor
  const glm::vec4 v[4] = {};
  const glm::vec4 start[4] = {};
  const glm::vec3 window_start[4] = {};
  // The apex's rise after one iteration.
  const auto rise = [&](std::uint32_t shared_by) {
    const std::uint32_t count[4] = {1u, 1u, 1u, shared_by};
    response::ContactConstants k{};
    k.h = 1e-3f;
    glm::vec4 given[3] = {}, correction[8] = {};
    response::solve_contact(pair, x, v, count, start, window_start, k, true, false,
                            response::kNoneSlid, given, correction);
    return correction[6].z;
  };
  const float alone = rise(1u);
  ASSERT_GT(alone, 0.0f) << "the apex should rise to the floor";
  EXPECT_EQ(rise(0u), alone);
  EXPECT_EQ(rise(4u), alone);
}

}  // namespace
}  // namespace deformcd
