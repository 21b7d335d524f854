// The GL collision backend against host references: every broad phase (the octree, the
// all-pairs baseline, octree-compact, bvh) finds exactly the face pairs that testing every pair
// of faces with the C++ narrow phase finds (the GLSL mirror performs the same float operations,
// so the segments agree bit for bit on llvmpipe), the face flags and counters agree with those
// pairs, the leaf boxes with boxes grown on the host; and the backend's boundaries: a full
// result buffer, several mask chunks, buffers over the limit, a single mesh, misuse.

#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/simulation_state.h"
#include "gl/collision_test_backends.h"
#include "gl/collision_test_worlds.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd::gl {
namespace {

using test::count_set;
using test::expect_same_pairs;
using test::flags_of;
using test::GlBackend;

constexpr BroadPhase kEveryMethod[] = {BroadPhase::kOctree, BroadPhase::kBrute,
                                       BroadPhase::kOctreeCompact, BroadPhase::kBvh};

bool lists_box_pairs(BroadPhase method) {
  return method == BroadPhase::kOctree || method == BroadPhase::kOctreeCompact;
}

class GlCollisionTest : public test_support::GlTest {};

TEST_F(GlCollisionTest, CrossingMeshesGiveTheHostPairsFlagsAndCounts) {
  GlBackend gl(context(), test::two_crossing_grids());
  const collision::CollisionData& data = gl.fixture.data;
  const std::vector<gpu::FacePair> expected = gl.expected();
  ASSERT_GT(expected.size(), 10u) << "the fixture's meshes should cross";
  const std::vector<std::uint32_t> expected_flags = flags_of(expected, data.faces.size());
  const std::uint32_t expected_box_pairs =
      test::overlapping_box_pairs(data, test::leaf_boxes_on_host(data, gl.fixture.vertices()));
  ASSERT_GT(expected_box_pairs, 0u);

  EXPECT_EQ(gl.collision.name(), "gl");
  EXPECT_NE(gl.collision.device().find("OpenGL"), std::string::npos) << gl.collision.device();
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
  // Host arrays are gathered into the backend's buffer.
  EXPECT_FALSE(gl.collision.positions_in_place());
}

TEST_F(GlCollisionTest, MeshesApartGiveNoPairsNoFlagsAndNoBoxPairs) {
  GlBackend gl(context(), test::two_separate_grids());
  ASSERT_TRUE(gl.expected().empty());
  for (BroadPhase method : kEveryMethod) {
    const std::string name(broadphase_name(method));
    EXPECT_TRUE(gl.pairs(method).empty()) << name;
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_EQ(counters.face_pairs, 0u) << name;
    EXPECT_EQ(counters.box_pairs, 0u) << name;
    EXPECT_EQ(counters.colliding_faces, 0u) << name;
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, std::vector<std::uint32_t>(gl.fixture.data.faces.size(), 0u)) << name;
  }
}

// A World's case: the positions are a GL simulation's SSBO 0 (a vec4 per node, body b's from
// node_offset), read in place. After a few substeps the leaf boxes are the host's boxes of the
// simulation's current positions, empty ones (leaf cells inside a mesh) included, and the pairs
// those of the current positions.
TEST_F(GlCollisionTest, LeafBoxesFollowASimulationsBufferReadInPlace) {
  const std::vector<BodyInit> bodies = test::two_crossing_grids();
  SimulationState world = assemble_simulation(bodies);
  for (std::size_t i = 0; i < world.velocities.size(); ++i) {
    const auto n = static_cast<std::uint32_t>(i);
    world.velocities[i] =
        glm::vec4(test::hash_unit(n, 21), test::hash_unit(n, 22), test::hash_unit(n, 23), 0.0f);
  }
  GlSimulation simulation(context());
  simulation.upload(world);
  test::GlBackend gl(context(), bodies);
  const std::vector<collision::PositionSource> sources =
      test::simulation_sources(simulation.node_buffers().gl_positions, world.objects);
  gl.collision.set_positions(sources);
  test::run_substeps(simulation, test::substep_constants(1e-3f, {0.0f, -9.81f, 0.0f}), 5);
  std::vector<glm::vec4> positions;
  simulation.download_positions(positions);
  ASSERT_NE(positions, world.positions) << "the substeps should move the nodes";
  for (std::size_t b = 0; b < world.objects.size(); ++b) {
    const gpu::ObjectInfo& o = world.objects[b];
    gl.fixture.positions[b].assign(positions.begin() + o.node_offset,
                                   positions.begin() + o.node_offset + o.node_count);
  }
  gl.fixture.refresh_views();
  const std::vector<gpu::Box> expected =
      test::leaf_boxes_on_host(gl.fixture.data, gl.fixture.vertices());

  gl.collision.detect(BroadPhase::kOctree);
  EXPECT_TRUE(gl.collision.positions_in_place());
  std::vector<gpu::MeshInfo> meshes;
  gl.collision.download_meshes(meshes);
  ASSERT_EQ(meshes.size(), 2u);
  EXPECT_EQ(meshes[1].position_offset, 4 * world.objects[1].node_offset);
  EXPECT_EQ(meshes[1].position_stride, 4u);
  std::vector<gpu::Box> boxes;
  gl.collision.download_boxes(boxes);
  ASSERT_EQ(boxes.size(), 64u * bodies.size());
  std::size_t empty = 0;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    EXPECT_EQ(boxes[k].min, expected[k].min) << "box " << k;
    EXPECT_EQ(boxes[k].max, expected[k].max) << "box " << k;
    empty += gl.fixture.data.box_rows[k].y == 0 ? 1 : 0;
  }
  EXPECT_GT(empty, 0u) << "the fixture should have leaf boxes without faces";
  expect_same_pairs(gl.pairs(BroadPhase::kOctree), gl.expected(), "moved");
  expect_same_pairs(gl.pairs(BroadPhase::kBvh), gl.expected(), "moved, bvh");
}

TEST_F(GlCollisionTest, AFullPairBufferGrowsAndTheRerunReturnsEveryPair) {
  GlBackend gl(context(), test::two_crossing_grids(), {.initial_pair_capacity = 1});
  const std::vector<gpu::FacePair> expected = gl.expected();
  EXPECT_EQ(gl.collision.face_pair_capacity(), 1u);
  for (BroadPhase method : kEveryMethod) {
    expect_same_pairs(gl.pairs(method), expected, std::string(broadphase_name(method)));
    EXPECT_GE(gl.collision.face_pair_capacity(), expected.size());
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, flags_of(expected, gl.fixture.data.faces.size()));
  }
}

TEST_F(GlCollisionTest, ThreeMeshesInOneMaskSlotChunkByChunkFindEveryPair) {
  GlBackend one_slot(context(), test::three_crossing_grids(), {.mask_slots = 1});
  GlBackend two_slots(context(), test::three_crossing_grids(), {.mask_slots = 2});
  GlBackend all_slots(context(), test::three_crossing_grids());
  const collision::CollisionData& data = one_slot.fixture.data;
  ASSERT_EQ(data.mesh_pairs.size(), 3u);
  const std::vector<gpu::FacePair> expected = one_slot.expected();
  // Every mesh pair crosses, so that each chunk has work.
  std::set<std::pair<std::uint32_t, std::uint32_t>> crossing_meshes;
  for (const gpu::FacePair& p : expected)
    crossing_meshes.emplace(data.faces[p.face_a].body, data.faces[p.face_b].body);
  ASSERT_EQ(crossing_meshes.size(), 3u);

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
  const test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  GlCollision collision(context(), {.max_buffer_bytes = 1024});
  collision.set_positions(f.host_sources());
  try {
    collision.upload(f.data);
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("GL collision: buffers larger than GlCollisionOptions::max_buffer_bytes "
                        "(1024 bytes)"),
              std::string::npos)
        << what;
    const std::string faces = std::to_string(f.data.faces.size());
    EXPECT_NE(what.find("Face Information (SSBO 7): " + std::to_string(16 * f.data.faces.size()) +
                        " bytes (" + faces + " x 16)"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("BoundingBox Mask (SSBO 11): 16384 bytes (4096 x 4)"), std::string::npos)
        << what;
    EXPECT_EQ(what.find("Collision Counters"), std::string::npos) << what;
  }
  // Nothing was allocated.
  EXPECT_EQ(collision.gl_face_flag_buffer(), 0u);
  EXPECT_EQ(collision.gl_face_pair_buffer(), 0u);
  EXPECT_THROW(collision.detect(BroadPhase::kOctree), Error);
}

TEST_F(GlCollisionTest, ASingleMeshHasNoPairs) {
  GlBackend gl(context(), {test::crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0})});
  ASSERT_TRUE(gl.fixture.data.mesh_pairs.empty());
  for (BroadPhase method : kEveryMethod) {
    EXPECT_TRUE(gl.pairs(method).empty());
    const gpu::CollisionCounters counters = gl.collision.counters();
    EXPECT_EQ(counters.face_pairs, 0u);
    EXPECT_EQ(counters.box_pairs, 0u);
    std::vector<std::uint32_t> flags;
    gl.collision.download_face_flags(flags);
    EXPECT_EQ(flags, std::vector<std::uint32_t>(gl.fixture.data.faces.size(), 0u));
  }
  // BBUpdate still runs over the mesh's boxes.
  std::vector<gpu::Box> boxes;
  gl.collision.detect(BroadPhase::kOctree);
  gl.collision.download_boxes(boxes);
  const std::vector<gpu::Box> expected =
      test::leaf_boxes_on_host(gl.fixture.data, gl.fixture.vertices());
  ASSERT_EQ(boxes.size(), expected.size());
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    EXPECT_EQ(boxes[k].min, expected[k].min) << "box " << k;
    EXPECT_EQ(boxes[k].max, expected[k].max) << "box " << k;
  }
}

TEST_F(GlCollisionTest, NoneResetsTheLastPassResults) {
  GlBackend gl(context(), test::two_crossing_grids());
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

// Runs `call` and expects an Error whose message contains every one of `parts`.
template <class Call>
void expect_error(Call&& call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "expected Error containing " << parts.front();
  } catch (const Error& e) {
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST_F(GlCollisionTest, MisuseThrowsNamingTheProblem) {
  EXPECT_THROW({ GlCollision bad(context(), {.mask_slots = 0}); }, Error);
  GlCollision collision(context());
  EXPECT_EQ(collision.gl_face_flag_buffer(), 0u);
  EXPECT_EQ(collision.face_pair_capacity(), 0u);
  EXPECT_THROW(collision.detect(BroadPhase::kOctree), Error);
  std::vector<gpu::FacePair> pairs;
  EXPECT_THROW(collision.download_face_pairs(pairs), Error);
  expect_error([&] { (void)collision.read_positions(0); }, {"mesh 0", "no positions"});

  // Hierarchies are needed.
  test::CollisionFixture f = test::collision_fixture(test::two_crossing_grids());
  collision::CollisionData bare = f.data;
  bare.bvh_nodes.clear();
  bare.mesh_bvhs.clear();
  expect_error([&] { collision.upload(bare); }, {"no hierarchies"});

  // Uploaded before any positions are set: a pass needs them.
  collision.upload(f.data);
  EXPECT_NE(collision.gl_face_flag_buffer(), 0u);
  EXPECT_NE(collision.gl_face_pair_buffer(), 0u);
  EXPECT_NE(collision.gl_face_pair_buffer(), collision.gl_face_flag_buffer());
  expect_error([&] { collision.detect(BroadPhase::kOctree); }, {"positions set for 0 meshes"});
  std::vector<collision::PositionSource> sources = f.host_sources();
  sources[1] = {};
  collision.set_positions(sources);
  expect_error([&] { collision.detect(BroadPhase::kOctree); }, {"mesh 1 ('grid 7')", "none set"});
  // Positions for another vertex count than the mesh's.
  sources = f.host_sources();
  sources[0].vertex_count -= 1;
  collision.set_positions(sources);
  expect_error([&] { collision.detect(BroadPhase::kOctree); },
               {"mesh 0 ('grid 1')", "set for 63 vertices, but the mesh has 64"});
  // A malformed source is refused where it is set.
  sources = f.host_sources();
  sources[1].stride_bytes = 14;
  expect_error([&] { collision.set_positions(sources); }, {"mesh 1", "stride of 14 bytes"});
  sources[1].stride_bytes = 8;
  expect_error([&] { collision.set_positions(sources); }, {"mesh 1", "stride of 8 bytes"});
}

}  // namespace
}  // namespace deformcd::gl
