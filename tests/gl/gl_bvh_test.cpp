// The GL backend's broad phases beyond the paper, against host references: bvh_refit.comp's
// boxes are collision::refit_bvh's bit for bit; the candidate lists hold exactly the face pairs
// the CPU algorithms would test; lists that overflow are grown and the pass rerun by
// complete_pass, never truncated; trees that deformation has degraded are rebuilt on the host.

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "collision_test_backends.h"
#include "collision_test_worlds.h"
#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "deformcd/error.h"
#include "gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "support/face_box_overlaps.h"

namespace deformcd::gl {
namespace {

using test::Backends;
using test::expect_same_pairs;
using test::flags_of;

// Runs `substeps` of the simulation from random velocities and returns the world at the
// positions reached.
WorldState deform(Backends& gl, WorldState world, int substeps) {
  for (std::size_t i = 0; i < world.velocities.size(); ++i) {
    const auto n = static_cast<std::uint32_t>(i);
    world.velocities[i] =
        glm::vec4(test::hash_unit(n, 31), test::hash_unit(n, 32), test::hash_unit(n, 33), 0.0f);
  }
  gl.simulation.upload(world);
  test::run_substeps(gl.simulation, test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}), substeps);
  gl.simulation.download_positions(world.positions);
  return world;
}

std::array<std::uint32_t, 8> bits(const gpu::Box& b) {
  return {std::bit_cast<std::uint32_t>(b.min.x), std::bit_cast<std::uint32_t>(b.min.y),
          std::bit_cast<std::uint32_t>(b.min.z), std::bit_cast<std::uint32_t>(b.min.w),
          std::bit_cast<std::uint32_t>(b.max.x), std::bit_cast<std::uint32_t>(b.max.y),
          std::bit_cast<std::uint32_t>(b.max.z), std::bit_cast<std::uint32_t>(b.max.w)};
}

class GlBvhTest : public test_support::GlTest {};

TEST_F(GlBvhTest, RefittedBoxesAreTheHostRefitBitForBit) {
  Backends gl(context(), test::three_crossing_grids());
  const WorldState moved = deform(gl, test::three_crossing_grids(), 5);
  ASSERT_NE(moved.positions, test::three_crossing_grids().positions);
  std::vector<gpu::Box> expected(moved.bvh_nodes.size());
  for (const gpu::BodyBvh& t : moved.body_bvhs)
    collision::refit_bvh(moved.bvh_nodes, t.root, t.node_count, moved.positions, moved.faces,
                         expected);

  gl.collision.detect(BroadPhase::kBvh);
  std::vector<gpu::Box> boxes;
  gl.collision.download_bvh_boxes(boxes);
  ASSERT_EQ(boxes.size(), expected.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    ASSERT_EQ(bits(boxes[i]), bits(expected[i])) << "node " << i;
  // A second pass (the visit counters cleared again) gives the same boxes.
  gl.collision.detect(BroadPhase::kBvh);
  std::vector<gpu::Box> again;
  gl.collision.download_bvh_boxes(again);
  for (std::size_t i = 0; i < again.size(); ++i)
    ASSERT_EQ(bits(again[i]), bits(boxes[i])) << "node " << i;
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), test::all_pairs_on_host(moved), "deformed");
}

// counters.candidates is what each method hands to the triangle test, as the CPU counts it.
TEST_F(GlBvhTest, CandidatesAreThePairsEachBroadPhaseTests) {
  const WorldState world = test::three_crossing_grids();
  Backends gl(context(), world);
  const auto candidates = [&](BroadPhase method) {
    gl.collision.detect(method);
    return gl.collision.counters().candidates;
  };
  const std::uint32_t bvh = candidates(BroadPhase::kBvh);
  EXPECT_EQ(bvh, test::face_box_overlaps(world));
  const std::uint32_t octree = candidates(BroadPhase::kOctree);
  EXPECT_EQ(candidates(BroadPhase::kOctreeCompact), octree);
  std::uint32_t all = 0;
  for (const gpu::BodyPair& p : world.body_pairs)
    all += world.objects[p.a].face_count * world.objects[p.b].face_count;
  EXPECT_EQ(candidates(BroadPhase::kBrute), all);
  // The leaf boxes hold many faces each: they cull less than the faces' own boxes.
  EXPECT_LT(bvh, octree);
  EXPECT_LT(octree, all);
}

TEST_F(GlBvhTest, OverflowingListsGrowAndCompletePassReturnsEveryPair) {
  const WorldState world = test::three_crossing_grids();
  const std::vector<gpu::FacePair> expected = test::all_pairs_on_host(world);
  ASSERT_GT(expected.size(), 10u);
  for (BroadPhase method : {BroadPhase::kBvh, BroadPhase::kOctreeCompact}) {
    const std::string name(broadphase_name(method));
    Backends gl(context(), world,
                {.initial_pair_capacity = 1,
                 .initial_candidate_capacity = 1,
                 .initial_box_pair_capacity = 1});
    EXPECT_EQ(gl.collision.candidate_capacity(), 1u);
    EXPECT_EQ(gl.collision.box_pair_capacity(), 1u);
    gl.collision.detect(method);
    gl.collision.complete_pass();
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_GE(gl.collision.candidate_capacity(), counters.candidates) << name;
    EXPECT_GE(gl.collision.face_pair_capacity(), counters.face_pairs) << name;
    if (method == BroadPhase::kOctreeCompact) {
      EXPECT_GE(gl.collision.box_pair_capacity(), counters.box_pairs) << name;
      EXPECT_GT(counters.box_pairs, 1u) << name;
    }
    std::vector<gpu::FacePair> pairs;
    gl.collision.download_face_pairs(pairs);
    expect_same_pairs(test::sorted(pairs), expected, name);
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, flags_of(expected, world.faces.size())) << name;
    // The grown lists hold the next pass without a rerun.
    const std::uint32_t capacity = gl.collision.candidate_capacity();
    expect_same_pairs(gl.pairs(method), expected, name + ", again");
    EXPECT_EQ(gl.collision.candidate_capacity(), capacity) << name;
  }
}

// Scrambling a body's nodes (each takes another node's position) leaves its tree's topology
// meaningless: the refitted boxes balloon, the check after the pass rebuilds that body's tree
// (only that one) on the current positions, and the pairs stay the host's.
TEST_F(GlBvhTest, ADegradedTreeIsRebuiltOnTheCurrentPositions) {
  const WorldState world = test::two_crossing_grids();
  WorldState scrambled = world;
  const gpu::ObjectInfo& body = world.objects[1];
  for (std::uint32_t i = 0; i < body.node_count; ++i) {
    const std::uint32_t from = body.node_offset + (i * 7 + 3) % body.node_count;
    scrambled.positions[body.node_offset + i] = world.positions[from];
  }
  const std::vector<gpu::FacePair> expected = test::all_pairs_on_host(scrambled);

  Backends gl(context(), world, {.bvh_check_interval = 2});
  gl.simulation.upload(scrambled);
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "first pass");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 0u) << "checked every second pass only";
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "second pass");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 1u);

  std::vector<gpu::BvhNode> nodes;
  gl.collision.download_bvh_nodes(nodes);
  const gpu::BodyBvh& t = world.body_bvhs[1];
  const std::vector<gpu::BvhNode> rebuilt = collision::build_bvh(
      scrambled.positions, scrambled.faces, body.face_offset, body.face_count, t.root);
  ASSERT_EQ(rebuilt.size(), t.node_count);
  for (std::uint32_t i = 0; i < nodes.size(); ++i) {
    const gpu::BvhNode& n = nodes[i];
    const gpu::BvhNode& e = i < t.root ? world.bvh_nodes[i] : rebuilt[i - t.root];
    ASSERT_TRUE(n.left == e.left && n.right == e.right && n.parent == e.parent && n.face == e.face)
        << "node " << i;
  }
  std::uint32_t leaves_moved = 0;
  for (std::uint32_t i = t.root; i < nodes.size(); ++i)
    leaves_moved += nodes[i].face != world.bvh_nodes[i].face ? 1u : 0u;
  EXPECT_GT(leaves_moved, 0u) << "the scrambled body's tree should change";
  // The rebuilt tree is as tight as a fresh one: no further rebuild.
  for (int pass = 0; pass < 4; ++pass)
    expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "rebuilt tree");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 1u);
}

TEST_F(GlBvhTest, GentleDeformationKeepsTheTrees) {
  Backends gl(context(), test::two_crossing_grids(), {.bvh_check_interval = 1});
  const WorldState moved = deform(gl, test::two_crossing_grids(), 5);
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), test::all_pairs_on_host(moved), "moved");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 0u);
}

TEST_F(GlBvhTest, ACheckIntervalOfZeroIsRejected) {
  GlSimulation simulation(context());
  EXPECT_THROW({ GlCollision bad(context(), simulation, {.bvh_check_interval = 0}); }, Error);
}

}  // namespace
}  // namespace deformcd::gl
