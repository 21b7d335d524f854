// The GL collision backend against host references: every broad phase (the octree, the
// all-pairs baseline, octree-compact, bvh) finds exactly the face pairs that testing every pair
// of faces with the C++ narrow phase finds (the GLSL mirror performs the same float operations, so
// the segments agree bit for bit on llvmpipe), the face flags and counters agree with those pairs,
// the leaf boxes with boxes grown on the host; and the backend's boundaries: a full result buffer,
// several mask chunks, buffers over the limit, a single body.

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "collision_test_backends.h"
#include "collision_test_worlds.h"
#include "deformcd/error.h"
#include "deformcd/world_state.h"
#include "gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

using test::Backends;
using test::count_set;
using test::expect_same_pairs;
using test::flags_of;

constexpr BroadPhase kEveryMethod[] = {BroadPhase::kOctree, BroadPhase::kBrute,
                                       BroadPhase::kOctreeCompact, BroadPhase::kBvh};

bool lists_box_pairs(BroadPhase method) {
  return method == BroadPhase::kOctree || method == BroadPhase::kOctreeCompact;
}

class GlCollisionTest : public test_support::GlTest {};

TEST_F(GlCollisionTest, CrossingBodiesGiveTheHostPairsFlagsAndCounts) {
  const WorldState world = test::two_crossing_grids();
  const std::vector<gpu::FacePair> expected = test::all_pairs_on_host(world);
  ASSERT_GT(expected.size(), 10u) << "the fixture's bodies should cross";
  const std::vector<std::uint32_t> expected_flags = flags_of(expected, world.faces.size());
  const std::uint32_t expected_box_pairs =
      test::overlapping_box_pairs(world, test::leaf_boxes_on_host(world, world.positions));
  ASSERT_GT(expected_box_pairs, 0u);

  Backends gl(context(), world);
  EXPECT_EQ(gl.collision.name(), "gl");
  for (BroadPhase method : kEveryMethod) {
    const std::string name(broadphase_name(method));
    expect_same_pairs(gl.pairs(method), expected, name);
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_EQ(counters.face_pairs, expected.size()) << name;
    EXPECT_EQ(counters.colliding_faces, count_set(expected_flags)) << name;
    EXPECT_EQ(counters.box_pairs, lists_box_pairs(method) ? expected_box_pairs : 0u) << name;
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, expected_flags) << name;
  }
}

TEST_F(GlCollisionTest, BodiesApartGiveNoPairsNoFlagsAndNoBoxPairs) {
  const WorldState world = test::two_separate_grids();
  ASSERT_TRUE(test::all_pairs_on_host(world).empty());
  Backends gl(context(), world);
  for (BroadPhase method : kEveryMethod) {
    const std::string name(broadphase_name(method));
    EXPECT_TRUE(gl.pairs(method).empty()) << name;
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_EQ(counters.face_pairs, 0u) << name;
    EXPECT_EQ(counters.box_pairs, 0u) << name;
    EXPECT_EQ(counters.colliding_faces, 0u) << name;
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, std::vector<std::uint32_t>(world.faces.size(), 0u)) << name;
  }
}

// The boxes follow the deformation: after a few substeps they are the host's boxes of the
// simulation's current positions, empty ones (leaf cells inside the body) included.
TEST_F(GlCollisionTest, LeafBoxesAreTheHostBoxesOfTheCurrentPositions) {
  WorldState world = test::two_crossing_grids();
  for (std::size_t i = 0; i < world.velocities.size(); ++i) {
    const auto n = static_cast<std::uint32_t>(i);
    world.velocities[i] =
        glm::vec4(test::hash_unit(n, 21), test::hash_unit(n, 22), test::hash_unit(n, 23), 0.0f);
  }
  Backends gl(context(), world);
  test::run_substeps(gl.simulation, test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}), 5);
  std::vector<glm::vec4> positions;
  gl.simulation.download_positions(positions);
  ASSERT_NE(positions, world.positions) << "the substeps should move the nodes";
  const std::vector<gpu::Box> expected = test::leaf_boxes_on_host(world, positions);

  gl.collision.detect(BroadPhase::kOctree);
  std::vector<gpu::Box> boxes;
  gl.collision.download_boxes(boxes);
  ASSERT_EQ(boxes.size(), 64u * world.body_count());
  std::size_t empty = 0;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    EXPECT_EQ(boxes[k].min, expected[k].min) << "box " << k;
    EXPECT_EQ(boxes[k].max, expected[k].max) << "box " << k;
    empty += world.box_rows[k].y == 0 ? 1 : 0;
  }
  EXPECT_GT(empty, 0u) << "the fixture should have leaf boxes without faces";

  // And the pairs are those of the current positions.
  WorldState moved = world;
  moved.positions = positions;
  expect_same_pairs(gl.pairs(BroadPhase::kOctree), test::all_pairs_on_host(moved), "moved");
}

TEST_F(GlCollisionTest, AFullPairBufferGrowsAndTheRerunReturnsEveryPair) {
  const WorldState world = test::two_crossing_grids();
  const std::vector<gpu::FacePair> expected = test::all_pairs_on_host(world);
  Backends gl(context(), world, {.initial_pair_capacity = 1});
  EXPECT_EQ(gl.collision.face_pair_capacity(), 1u);
  for (BroadPhase method : kEveryMethod) {
    expect_same_pairs(gl.pairs(method), expected, std::string(broadphase_name(method)));
    EXPECT_GE(gl.collision.face_pair_capacity(), expected.size());
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, flags_of(expected, world.faces.size()));
  }
}

TEST_F(GlCollisionTest, ThreeBodiesInOneMaskSlotChunkByChunkFindEveryPair) {
  const WorldState world = test::three_crossing_grids();
  ASSERT_EQ(world.body_pairs.size(), 3u);
  const std::vector<gpu::FacePair> expected = test::all_pairs_on_host(world);
  // Every body pair crosses, so that each chunk has work.
  std::set<std::pair<std::uint32_t, std::uint32_t>> crossing_bodies;
  for (const gpu::FacePair& p : expected) {
    crossing_bodies.emplace(world.faces[p.face_a].body, world.faces[p.face_b].body);
  }
  ASSERT_EQ(crossing_bodies.size(), 3u);

  Backends one_slot(context(), world, {.mask_slots = 1});
  Backends two_slots(context(), world, {.mask_slots = 2});
  Backends all_slots(context(), world);
  expect_same_pairs(one_slot.pairs(BroadPhase::kOctree), expected, "octree, 1 slot");
  const gpu::CollisionCounters one_slot_counters = one_slot.collision.counters();
  expect_same_pairs(two_slots.pairs(BroadPhase::kOctree), expected, "octree, 2 slots");
  expect_same_pairs(all_slots.pairs(BroadPhase::kOctree), expected, "octree, 64 slots");
  EXPECT_EQ(one_slot_counters.box_pairs, all_slots.collision.counters().box_pairs);
  expect_same_pairs(one_slot.pairs(BroadPhase::kBrute), expected, "brute");
  expect_same_pairs(one_slot.pairs(BroadPhase::kOctreeCompact), expected, "octree-compact");
  EXPECT_EQ(one_slot.collision.counters().box_pairs, one_slot_counters.box_pairs);
  expect_same_pairs(one_slot.pairs(BroadPhase::kBvh), expected, "bvh");
}

// 1024 bytes: the faces (216 x 16 bytes) and the one mask slot (16 KiB) are over it, the
// counters are not, and the default face-pair capacity shrinks to fit it.
TEST_F(GlCollisionTest, BuffersOverTheLimitAreNamedWithTheirSizes) {
  const WorldState world = test::two_crossing_grids();
  GlSimulation simulation(context());
  simulation.upload(world);
  GlCollision collision(context(), simulation, {.max_buffer_bytes = 1024});
  try {
    collision.upload(world);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("GL collision: buffers larger than GlCollisionOptions::max_buffer_bytes "
                        "(1024 bytes)"),
              std::string::npos)
        << what;
    const std::string faces = std::to_string(world.faces.size());
    EXPECT_NE(what.find("Face Information (SSBO 7): " + std::to_string(16 * world.faces.size()) +
                        " bytes (" + faces + " x 16)"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("BoundingBox Mask (SSBO 11): 16384 bytes (4096 x 4)"), std::string::npos)
        << what;
    EXPECT_EQ(what.find("Collision Counters"), std::string::npos) << what;
  }
  // Nothing was allocated.
  EXPECT_EQ(collision.gl_face_flag_buffer(), 0u);
  EXPECT_THROW(collision.detect(BroadPhase::kOctree), Error);
}

TEST_F(GlCollisionTest, ASingleBodyHasNoPairs) {
  const WorldState world = assemble_world({test::crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0})});
  ASSERT_TRUE(world.body_pairs.empty());
  Backends gl(context(), world);
  for (BroadPhase method : kEveryMethod) {
    EXPECT_TRUE(gl.pairs(method).empty());
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_EQ(counters.face_pairs, 0u);
    EXPECT_EQ(counters.box_pairs, 0u);
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, std::vector<std::uint32_t>(world.faces.size(), 0u));
  }
  // BBUpdate still runs over the body's boxes.
  std::vector<gpu::Box> boxes;
  gl.collision.detect(BroadPhase::kOctree);
  gl.collision.download_boxes(boxes);
  const std::vector<gpu::Box> expected = test::leaf_boxes_on_host(world, world.positions);
  ASSERT_EQ(boxes.size(), expected.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    EXPECT_EQ(boxes[k].min, expected[k].min) << "box " << k;
    EXPECT_EQ(boxes[k].max, expected[k].max) << "box " << k;
  }
}

TEST_F(GlCollisionTest, NoneResetsTheLastPassResults) {
  const WorldState world = test::two_crossing_grids();
  Backends gl(context(), world);
  ASSERT_FALSE(gl.pairs(BroadPhase::kBvh).empty());
  EXPECT_TRUE(gl.pairs(BroadPhase::kNone).empty());
  const gpu::CollisionCounters counters = gl.collision.counters();
  EXPECT_EQ(
      counters.face_pairs + counters.box_pairs + counters.colliding_faces + counters.candidates,
      0u);
  std::vector<std::uint32_t> flags;
  gl.collision.download_face_flags(flags);
  EXPECT_EQ(count_set(flags), 0u);
}

TEST_F(GlCollisionTest, MisuseThrowsNamingTheProblem) {
  GlSimulation simulation(context());
  EXPECT_THROW({ GlCollision bad(context(), simulation, {.mask_slots = 0}); }, Error);
  GlCollision collision(context(), simulation);
  EXPECT_EQ(collision.gl_face_flag_buffer(), 0u);
  EXPECT_EQ(collision.face_pair_capacity(), 0u);
  EXPECT_THROW(collision.detect(BroadPhase::kOctree), Error);
  std::vector<gpu::FacePair> pairs;
  EXPECT_THROW(collision.download_face_pairs(pairs), Error);

  const WorldState world = test::two_crossing_grids();
  collision.upload(world);  // the simulation has no positions yet
  EXPECT_NE(collision.gl_face_flag_buffer(), 0u);
  try {
    collision.detect(BroadPhase::kOctree);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no positions"), std::string::npos) << e.what();
  }
  // Positions of a smaller world: too few nodes for the faces.
  simulation.upload(assemble_world({test::crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0})}));
  try {
    collision.detect(BroadPhase::kOctree);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(world.node_count()) + " nodes"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace deformcd::gl
