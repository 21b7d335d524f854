// The GL backend's broad phases beyond the paper, against host references: bvh_refit.comp's
// boxes are collision::refit_bvh's bit for bit; the candidate lists hold exactly the face pairs
// the CPU algorithms would test; lists that overflow are grown and the pass rerun by
// complete_pass, never truncated; trees that deformation has degraded are rebuilt on the host
// (collision::BvhUpkeep) from the pass's positions, wherever they come from.

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "deformcd/error.h"
#include "gl/collision_test_backends.h"
#include "gl/collision_test_worlds.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "support/face_box_overlaps.h"

namespace deformcd::gl {
namespace {

using test::expect_same_pairs;
using test::flags_of;
using test::GlBackend;

std::array<std::uint32_t, 8> bits(const gpu::Box& b) {
  return {std::bit_cast<std::uint32_t>(b.min.x), std::bit_cast<std::uint32_t>(b.min.y),
          std::bit_cast<std::uint32_t>(b.min.z), std::bit_cast<std::uint32_t>(b.min.w),
          std::bit_cast<std::uint32_t>(b.max.x), std::bit_cast<std::uint32_t>(b.max.y),
          std::bit_cast<std::uint32_t>(b.max.z), std::bit_cast<std::uint32_t>(b.max.w)};
}

class GlBvhTest : public test_support::GlTest {};

TEST_F(GlBvhTest, RefittedBoxesAreTheHostRefitBitForBit) {
  GlBackend gl(context(), test::three_crossing_grids());
  test::jiggle(gl.fixture, 0.01f, 3);  // the host arrays, read by the next pass
  const collision::CollisionData& d = gl.fixture.data;
  std::vector<gpu::Box> expected(d.bvh_nodes.size());
  for (const gpu::BodyBvh& t : d.mesh_bvhs)
    collision::refit_bvh(d.bvh_nodes, t.root, t.node_count, gl.fixture.vertices(), d.faces,
                         expected);

  gl.collision.detect(BroadPhase::kBvh);
  std::vector<gpu::Box> boxes;
  gl.collision.download_bvh_boxes(boxes);
  ASSERT_EQ(boxes.size(), expected.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    ASSERT_EQ(bits(boxes[i]), bits(expected[i])) << "node " << i;
  // A second pass gives the same boxes.
  gl.collision.detect(BroadPhase::kBvh);
  std::vector<gpu::Box> again;
  gl.collision.download_bvh_boxes(again);
  for (std::size_t i = 0; i < again.size(); ++i)
    ASSERT_EQ(bits(again[i]), bits(boxes[i])) << "node " << i;
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), gl.expected(), "deformed");
}

// counters.candidates is what each method hands to the triangle test, as the CPU counts it.
TEST_F(GlBvhTest, CandidatesAreThePairsEachBroadPhaseTests) {
  GlBackend gl(context(), test::three_crossing_grids());
  const auto candidates = [&](BroadPhase method) {
    gl.collision.detect(method);
    return gl.collision.counters().candidates;
  };
  const std::uint32_t bvh = candidates(BroadPhase::kBvh);
  EXPECT_EQ(bvh, test::face_box_overlaps(gl.fixture.data, gl.fixture.vertices()));
  const std::uint32_t octree = candidates(BroadPhase::kOctree);
  EXPECT_EQ(candidates(BroadPhase::kOctreeCompact), octree);
  std::uint32_t all = 0;
  for (const gpu::BodyPair& p : gl.fixture.data.mesh_pairs)
    all += gl.fixture.data.meshes[p.a].face_count * gl.fixture.data.meshes[p.b].face_count;
  EXPECT_EQ(candidates(BroadPhase::kBrute), all);
  // The leaf boxes hold many faces each: they cull less than the faces' own boxes.
  EXPECT_LT(bvh, octree);
  EXPECT_LT(octree, all);
}

TEST_F(GlBvhTest, OverflowingListsGrowAndCompletePassReturnsEveryPair) {
  for (BroadPhase method : {BroadPhase::kBvh, BroadPhase::kOctreeCompact}) {
    const std::string name(broadphase_name(method));
    GlBackend gl(context(), test::three_crossing_grids(),
                 {.initial_pair_capacity = 1,
                  .initial_candidate_capacity = 1,
                  .initial_box_pair_capacity = 1});
    const std::vector<gpu::FacePair> expected = gl.expected();
    ASSERT_GT(expected.size(), 10u);
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
    EXPECT_EQ(flags, flags_of(expected, gl.fixture.data.faces.size())) << name;
    // The grown lists hold the next pass without a rerun.
    const std::uint32_t capacity = gl.collision.candidate_capacity();
    expect_same_pairs(gl.pairs(method), expected, name + ", again");
    EXPECT_EQ(gl.collision.candidate_capacity(), capacity) << name;
  }
}

// The reruns of an overflowed pass read the positions it staged: host arrays changed after
// detect() do not leak into them.
TEST_F(GlBvhTest, ARerunReadsThePositionsOfItsPass) {
  GlBackend gl(context(), test::two_crossing_grids(),
               {.initial_pair_capacity = 1, .initial_candidate_capacity = 1});
  const std::vector<gpu::FacePair> expected = gl.expected();
  gl.collision.detect(BroadPhase::kBvh);
  test::jiggle(gl.fixture, 0.03f, 11);  // after the pass was issued
  std::vector<gpu::FacePair> pairs;
  gl.collision.download_face_pairs(pairs);
  EXPECT_GT(gl.collision.face_pair_capacity(), 1u) << "the pass should have been rerun";
  expect_same_pairs(test::sorted(pairs), expected, "rerun");
}

// Where the positions come from in the rebuild test.
enum class Source { kHost, kOneBuffer, kTwoBuffers };

class GlBvhRebuildTest : public test_support::GlTest,
                         public ::testing::WithParamInterface<Source> {};

// Scrambling a mesh's vertices (each takes another vertex's position) leaves its tree's topology
// meaningless: the refitted boxes balloon, the check after the pass rebuilds that mesh's tree
// (only that one) on the pass's positions, and the pairs stay the host's.
TEST_P(GlBvhRebuildTest, ADegradedTreeIsRebuiltOnThePassPositions) {
  GlBackend gl(context(), test::two_crossing_grids(), {.bvh_check_interval = 2});
  const collision::CollisionData& d = gl.fixture.data;
  const std::vector<gpu::BvhNode> built = d.bvh_nodes;
  std::vector<glm::vec4>& mesh = gl.fixture.positions[1];
  const std::vector<glm::vec4> original = mesh;
  for (std::size_t i = 0; i < mesh.size(); ++i)
    mesh[i] = original[(i * 7 + 3) % mesh.size()];
  const std::vector<gpu::FacePair> expected = gl.expected();
  std::unique_ptr<test::GlPositionBuffer> one;
  std::unique_ptr<test::GlPositionBuffer> two;
  if (GetParam() == Source::kOneBuffer) {
    one = std::make_unique<test::GlPositionBuffer>(gl.fixture.positions, 12, 12);
    gl.collision.set_positions(one->sources());
  } else if (GetParam() == Source::kTwoBuffers) {
    one = std::make_unique<test::GlPositionBuffer>(
        std::vector<std::vector<glm::vec4>>{gl.fixture.positions[0]}, 0, 16);
    two = std::make_unique<test::GlPositionBuffer>(
        std::vector<std::vector<glm::vec4>>{gl.fixture.positions[1]}, 4, 12);
    gl.collision.set_positions({one->source(0), two->source(0)});
  }

  expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "first pass");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 0u) << "checked every second pass only";
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "second pass");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 1u);

  std::vector<gpu::BvhNode> nodes;
  gl.collision.download_bvh_nodes(nodes);
  const gpu::BodyBvh& t = d.mesh_bvhs[1];
  const gpu::MeshInfo& m = d.meshes[1];
  const std::vector<gpu::BvhNode> rebuilt =
      collision::build_bvh(gl.fixture.vertices(), d.faces, m.face_offset, m.face_count, t.root);
  ASSERT_EQ(rebuilt.size(), t.node_count);
  for (std::uint32_t i = 0; i < nodes.size(); ++i) {
    const gpu::BvhNode& n = nodes[i];
    const gpu::BvhNode& e = i < t.root ? built[i] : rebuilt[i - t.root];
    ASSERT_TRUE(n.left == e.left && n.right == e.right && n.parent == e.parent && n.face == e.face)
        << "node " << i;
  }
  std::uint32_t leaves_moved = 0;
  for (std::uint32_t i = t.root; i < nodes.size(); ++i)
    leaves_moved += nodes[i].face != built[i].face ? 1u : 0u;
  EXPECT_GT(leaves_moved, 0u) << "the scrambled mesh's tree should change";
  // The rebuilt tree is as tight as a fresh one: no further rebuild.
  for (int pass = 0; pass < 4; ++pass)
    expect_same_pairs(gl.pairs(BroadPhase::kBvh), expected, "rebuilt tree");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 1u);
}

std::string source_name(const ::testing::TestParamInfo<Source>& param) {
  switch (param.param) {
    case Source::kHost:
      return "HostArrays";
    case Source::kOneBuffer:
      return "OneGlBuffer";
    case Source::kTwoBuffers:
      return "TwoGlBuffers";
  }
  return "Unknown";
}

INSTANTIATE_TEST_SUITE_P(EverySource, GlBvhRebuildTest,
                         ::testing::Values(Source::kHost, Source::kOneBuffer, Source::kTwoBuffers),
                         source_name);

TEST_F(GlBvhTest, GentleDeformationKeepsTheTrees) {
  GlBackend gl(context(), test::two_crossing_grids(), {.bvh_check_interval = 1});
  test::jiggle(gl.fixture, 0.005f, 17);
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), gl.expected(), "moved");
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), gl.expected(), "moved, again");
  EXPECT_EQ(gl.collision.bvh_rebuilds(), 0u);
}

TEST_F(GlBvhTest, ACheckIntervalOfZeroIsRejected) {
  EXPECT_THROW({ GlCollision bad(context(), {.bvh_check_interval = 0}); }, Error);
}

}  // namespace
}  // namespace deformcd::gl
