// What GlCollision::upload checks before allocating (no GL needed): the collision lists'
// consistency, the buffer sizes, and the chunks the body pairs are dispatched in.

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/world_state.h"
#include "gpu/gl/collision_dispatch_plan.h"
#include "gpu/gl/collision_upload_checks.h"
#include "support/world_fixtures.h"

namespace deformcd::gl {
namespace {

// Bodies of 1 x 1 x 1, 2 x 1 x 1 and 1 x 1 x 3 cubes: different face and row counts.
WorldState three_body_world() {
  BodyInit a, b, c;
  a.body = build_body(test::tet_grid(1, 1, 1, 1.0));
  b.body = build_body(test::tet_grid(2, 1, 1, 1.0, {3.0, 0.0, 0.0}));
  c.body = build_body(test::tet_grid(1, 1, 3, 1.0, {0.0, 3.0, 0.0}));
  return assemble_world({a, b, c});
}

TEST(CollisionBufferSizes, ListsEveryBufferWithItsBindingAndSize) {
  const WorldState w = three_body_world();
  const std::vector<BufferSize> sizes = collision_buffer_sizes(w, 100, 2);
  const std::vector<std::uint32_t> bindings = {4, 5, 7, 8, 9, 10, 11, 21, 22, 23, 24};
  const std::vector<std::uint64_t> bytes = {
      32 * 64 * 3, 4 * w.faces.size(), 16 * w.faces.size(), 48 * 3, 8 * w.box_faces.size(),
      48 * 100,    4 * 64 * 64 * 2,    8 * w.faces.size(),  8 * 3,  16,
      8 * 64 * 3};
  ASSERT_EQ(sizes.size(), bindings.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(sizes[i].binding, bindings[i]) << sizes[i].name;
    EXPECT_EQ(sizes[i].bytes(), bytes[i]) << sizes[i].name;
  }
  EXPECT_EQ(sizes[5].name, "Face Pair");
  EXPECT_EQ(sizes[6].name, "BoundingBox Mask");
}

TEST(CheckCollisionConsistency, AcceptsAssembledWorlds) {
  EXPECT_NO_THROW(check_collision_consistency(three_body_world()));
  EXPECT_NO_THROW(check_collision_consistency(assemble_world({})));
}

// Each broken world is rejected with a message containing `expected`.
void expect_rejected(const std::function<void(WorldState&)>& breaks, const std::string& expected) {
  WorldState w = three_body_world();
  breaks(w);
  try {
    check_collision_consistency(w);
    ADD_FAILURE() << "expected Error containing: " << expected;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(CheckCollisionConsistency, NamesWhatDoesNotFit) {
  expect_rejected([](WorldState& w) { w.face_boxes.pop_back(); }, "face_boxes has");
  expect_rejected([](WorldState& w) { w.box_rows.pop_back(); }, "box_rows has");
  expect_rejected([](WorldState& w) { w.faces[5].c = 999; }, "face 5 has node 999");
  expect_rejected([](WorldState& w) { w.objects[1].face_count += 1000; }, "object 1's faces");
  expect_rejected([](WorldState& w) { w.objects[2].box_face_count += 1; },
                  "object 2's box-face rows");
  expect_rejected([](WorldState& w) { w.objects[1].box_offset = 0; },
                  "object 1 has leaf boxes [0, +64)");
  // A box's rows reaching into the next body's.
  expect_rejected([](WorldState& w) { w.box_rows[63].y += 1; }, "leaf box 63 of object 0");
  expect_rejected(
      [](WorldState& w) {
        const std::uint32_t row = w.box_rows[64].x;  // object 1's first listed box is box 0
        w.box_faces[row].box = 5;
      },
      "names box 5");
  expect_rejected(
      [](WorldState& w) {
        const std::uint32_t face = w.box_faces[w.box_rows[64].x].face;
        w.face_boxes[face] = glm::uvec2(0u);
      },
      "lacks bit 0");
  expect_rejected([](WorldState& w) { w.body_pairs[2] = {2, 1}; }, "body pair 2 is (2, 1)");
  expect_rejected([](WorldState& w) { w.body_pairs[0] = {0, 3}; }, "body pair 0 is (0, 3)");
}

TEST(PlanPairChunks, CoversThePairsInChunksWithTheirLargestCounts) {
  const WorldState w = three_body_world();  // pairs (0,1), (0,2), (1,2)
  const std::uint32_t f0 = w.objects[0].face_count;
  const std::uint32_t f1 = w.objects[1].face_count;
  const std::uint32_t f2 = w.objects[2].face_count;
  EXPECT_EQ(plan_pair_chunks(w.body_pairs, w.objects, 2, &gpu::ObjectInfo::face_count),
            (std::vector<PairChunk>{{0, 2, f0, std::max(f1, f2)}, {2, 1, f1, f2}}));
  EXPECT_EQ(plan_pair_chunks(w.body_pairs, w.objects, 64, &gpu::ObjectInfo::box_face_count),
            (std::vector<PairChunk>{
                {0, 3, std::max(w.objects[0].box_face_count, w.objects[1].box_face_count),
                 std::max(w.objects[1].box_face_count, w.objects[2].box_face_count)}}));
  EXPECT_TRUE(plan_pair_chunks({}, w.objects, 1, &gpu::ObjectInfo::face_count).empty());
  EXPECT_THROW((void)plan_pair_chunks(w.body_pairs, w.objects, 0, &gpu::ObjectInfo::face_count),
               Error);
}

TEST(CheckChunksFit, NamesTheShaderTheAxisAndTheLimit) {
  const std::vector<PairChunk> chunks = {{0, 2, 64, 64}, {2, 1, 80, 8}};
  EXPECT_NO_THROW(check_chunks_fit("s.comp", chunks, {8, 8, 1}, {10, 8, 2}));
  try {
    check_chunks_fit("collision/tri_tri_brute.comp", chunks, {8, 8, 1}, {9, 8, 2});
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'collision/tri_tri_brute.comp' would need 10 work groups along x for "
                        "body pairs 2 to 2"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("GL_MAX_COMPUTE_WORK_GROUP_COUNT of 9"), std::string::npos) << what;
  }
  EXPECT_THROW(check_chunks_fit("s.comp", chunks, {8, 8, 1}, {10, 8, 1}), GlError);  // z
}

TEST(GroupsCovering, RoundsUp) {
  EXPECT_EQ(groups_covering(0, 8), 0u);
  EXPECT_EQ(groups_covering(8, 8), 1u);
  EXPECT_EQ(groups_covering(9, 8), 2u);
  EXPECT_EQ(groups_covering(0xFFFFFFFFu, 4), 0x40000000u);
}

}  // namespace
}  // namespace deformcd::gl
