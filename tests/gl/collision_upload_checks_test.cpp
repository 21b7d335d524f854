// What GlCollision::upload checks before allocating (no GL needed): the collision data's
// consistency, the buffer sizes, and the chunks the mesh pairs are dispatched in.

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/collision/collision_data.h"
#include "deformcd/body.h"
#include "deformcd/error.h"
#include "deformcd/simulation_state.h"
#include "gpu/gl/bvh_work_order.h"
#include "gpu/gl/collision_dispatch_plan.h"
#include "gpu/gl/collision_upload_checks.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::gl {
namespace {

using collision::CollisionData;

// The surfaces of 1 x 1 x 1, 2 x 1 x 1 and 1 x 1 x 3 cubes: different face and row counts.
CollisionData three_meshes() {
  BodyInit a, b, c;
  a.body = build_body(test::tet_grid(1, 1, 1, 1.0));
  b.body = build_body(test::tet_grid(2, 1, 1, 1.0, {3.0, 0.0, 0.0}));
  c.body = build_body(test::tet_grid(1, 1, 3, 1.0, {0.0, 3.0, 0.0}));
  return test::collision_fixture({a, b, c}).data;
}

TEST(CollisionBufferSizes, ListsEveryBufferWithItsBindingAndSize) {
  const CollisionData w = three_meshes();
  const std::vector<BufferSize> sizes = collision_buffer_sizes(
      w, {.face_pairs = 100, .mask_slots = 2, .candidates = 7, .box_pairs = 9});
  const std::vector<std::uint32_t> bindings = {4,  5,  7,  8,  9,  10, 11, 21, 22, 23,
                                               24, 25, 26, 27, 28, 29, 30, 31, 32, 33};
  const std::uint64_t nodes = w.bvh_nodes.size();
  ASSERT_EQ(nodes, 2 * w.faces.size() - 3);  // 2 x faces - 1 per mesh
  // clang-format off
  const std::vector<std::uint64_t> bytes = {
      32 * 64 * 3, 4 * w.faces.size(), 16 * w.faces.size(), 32 * 3, 8 * w.box_faces.size(),
      48 * 100, 4 * 64 * 64 * 2, 8 * w.faces.size(), 8 * 3, 16, 8 * 64 * 3,
      16 * nodes, 32 * nodes, 16 * 3, 8 * 7, 4 * 12, 8 * 9, 4 * (nodes - w.faces.size()), 8 * 3,
      4 * w.faces.size()};
  // clang-format on
  ASSERT_EQ(sizes.size(), bindings.size());
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(sizes[i].binding, bindings[i]) << sizes[i].name;
    EXPECT_EQ(sizes[i].bytes(), bytes[i]) << sizes[i].name;
  }
  EXPECT_EQ(sizes[3].name, "Mesh Information");
  EXPECT_EQ(sizes[5].name, "Face Pair");
  EXPECT_EQ(sizes[6].name, "BoundingBox Mask");
  EXPECT_EQ(sizes[14].name, "Candidate Pair");
  EXPECT_EQ(sizes[16].name, "Box Pair List");
  EXPECT_EQ(sizes[18].name, "Touching Pairs");
  EXPECT_EQ(sizes[19].name, "BVH Leaves");
}

TEST(CheckCollisionData, AcceptsLaidOutMeshes) {
  EXPECT_NO_THROW(check_collision_data(three_meshes()));
}

// Each broken data set is rejected with a message containing `expected`.
void expect_rejected(const std::function<void(CollisionData&)>& breaks,
                     const std::string& expected) {
  CollisionData w = three_meshes();
  breaks(w);
  try {
    check_collision_data(w);
    ADD_FAILURE() << "expected Error containing: " << expected;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(CheckCollisionData, NamesWhatDoesNotFit) {
  expect_rejected([](CollisionData& w) { w.face_boxes.pop_back(); }, "face_boxes has");
  expect_rejected([](CollisionData& w) { w.box_rows.pop_back(); }, "box_rows has");
  expect_rejected([](CollisionData& w) { w.faces[5].c = 999; }, "face 5 has vertex 999");
  // Local indices: mesh 0 has 8 vertices, so vertex 8 is out of its range (mesh 1 has 12).
  expect_rejected([](CollisionData& w) { w.faces[0].a = 8; }, "face 0 has vertex 8, but mesh 0");
  expect_rejected([](CollisionData& w) { w.faces[3].body = 7; }, "face 3 names mesh 7");
  expect_rejected([](CollisionData& w) { w.faces[3].body = 1; },
                  "face 3 names mesh 1, whose faces are");
  expect_rejected([](CollisionData& w) { w.meshes[1].face_count += 1000; }, "mesh 1's faces");
  expect_rejected([](CollisionData& w) { w.meshes[2].box_face_count += 1; },
                  "mesh 2's box-face rows");
  // A box's rows reaching into the next mesh's.
  expect_rejected([](CollisionData& w) { w.box_rows[63].y += 1; }, "leaf box 63 of mesh 0");
  expect_rejected(
      [](CollisionData& w) {
        const std::uint32_t row = w.box_rows[64].x;  // mesh 1's first listed box is box 0
        w.box_faces[row].box = 5;
      },
      "names box 5");
  expect_rejected(
      [](CollisionData& w) {
        const std::uint32_t face = w.box_faces[w.box_rows[64].x].face;
        w.face_boxes[face] = glm::uvec2(0u);
      },
      "lacks bit 0");
  expect_rejected([](CollisionData& w) { w.mesh_pairs[2] = {2, 1}; }, "mesh pair 2 is (2, 1)");
  expect_rejected([](CollisionData& w) { w.mesh_pairs[0] = {0, 3}; }, "mesh pair 0 is (0, 3)");
  expect_rejected(
      [](CollisionData& w) {
        w.bvh_nodes.clear();
        w.mesh_bvhs.clear();
      },
      "no hierarchies");
}

// The BVH checks: what the refit's walks and the traversal's fixed stack rely on.
TEST(CheckCollisionData, NamesWhatIsWrongWithABvh) {
  expect_rejected([](CollisionData& w) { w.mesh_bvhs.pop_back(); }, "mesh_bvhs has 2 entries");
  expect_rejected([](CollisionData& w) { w.mesh_bvhs[1].root += 1; }, "mesh 1's BVH has nodes");
  expect_rejected([](CollisionData& w) { w.mesh_bvhs[2].node_count -= 2; },
                  "mesh 2's BVH has nodes");
  expect_rejected([](CollisionData& w) { w.mesh_bvhs[0].depth = 64; }, "has depth 64");
  expect_rejected([](CollisionData& w) { w.mesh_bvhs[0].depth = 1; }, "but its BodyBvh says 1");
  expect_rejected([](CollisionData& w) { w.bvh_nodes[w.mesh_bvhs[1].root].parent = 0; },
                  "has parent 0, not an earlier node of the tree (or none for the root)");
  expect_rejected(
      [](CollisionData& w) {
        const gpu::BvhNode root = w.bvh_nodes[0];
        w.bvh_nodes[root.left].parent = root.right;  // the child no longer names its parent
      },
      "node 0 has child");
  expect_rejected(
      [](CollisionData& w) {
        const std::uint32_t root = w.mesh_bvhs[1].root;
        w.bvh_nodes[root].right = w.bvh_nodes[root].left;
      },
      "has the same node as both children");
  expect_rejected(
      [](CollisionData& w) {
        // Two leaves of the same face: another face is missing.
        std::uint32_t first_leaf = gpu::kBvhInternal;
        for (std::uint32_t i = 0; i < w.mesh_bvhs[0].node_count; ++i) {
          if (w.bvh_nodes[i].face == gpu::kBvhInternal) continue;
          if (first_leaf == gpu::kBvhInternal) {
            first_leaf = i;
          } else {
            w.bvh_nodes[i].face = w.bvh_nodes[first_leaf].face;
            return;
          }
        }
      },
      "not a face of the mesh listed once");
  expect_rejected([](CollisionData& w) { w.bvh_nodes.push_back(w.bvh_nodes.back()); },
                  "but the meshes' trees have");
}

// The refit's levels: every internal node once, each after its internal children (its leaves
// come from the first dispatch); the traversal's leaves: each mesh's, in preorder, from its face
// offset.
TEST(PlanBvhWorkOrder, OrdersTheRefitByLevelAndTheLeavesInPreorder) {
  const CollisionData w = three_meshes();
  const BvhWorkOrder plan = plan_bvh_work_order(w.bvh_nodes, w.mesh_bvhs, w.meshes, w.faces.size());
  ASSERT_EQ(plan.refit_order.size(), w.bvh_nodes.size() - w.faces.size());
  std::vector<int> level_of(w.bvh_nodes.size(), -1);
  std::uint32_t next = 0;
  for (std::size_t l = 0; l < plan.levels.size(); ++l) {
    ASSERT_EQ(plan.levels[l].x, next);
    ASSERT_GT(plan.levels[l].y, 0u);
    for (std::uint32_t k = next; k < next + plan.levels[l].y; ++k) {
      const std::uint32_t node = plan.refit_order[k];
      ASSERT_EQ(w.bvh_nodes[node].face, gpu::kBvhInternal);
      ASSERT_EQ(level_of[node], -1) << "node " << node << " listed twice";
      level_of[node] = static_cast<int>(l);
    }
    next += plan.levels[l].y;
  }
  for (std::uint32_t node : plan.refit_order) {
    for (std::uint32_t child : {w.bvh_nodes[node].left, w.bvh_nodes[node].right}) {
      if (w.bvh_nodes[child].face == gpu::kBvhInternal) {
        EXPECT_LT(level_of[child], level_of[node]) << "node " << node << ", child " << child;
      }
    }
  }
  ASSERT_EQ(plan.leaves.size(), w.faces.size());
  for (std::size_t b = 0; b < w.mesh_count(); ++b) {
    std::vector<std::uint32_t> leaves;
    const gpu::BodyBvh& t = w.mesh_bvhs[b];
    for (std::uint32_t i = t.root; i < t.root + t.node_count; ++i) {
      if (w.bvh_nodes[i].face != gpu::kBvhInternal) leaves.push_back(i);
    }
    const auto first = plan.leaves.begin() + w.meshes[b].face_offset;
    EXPECT_EQ(std::vector<std::uint32_t>(first, first + w.meshes[b].face_count), leaves);
  }
}

TEST(PlanPairChunks, CoversThePairsInChunksWithTheirLargestCounts) {
  const CollisionData w = three_meshes();  // pairs (0,1), (0,2), (1,2)
  const std::uint32_t f0 = w.meshes[0].face_count;
  const std::uint32_t f1 = w.meshes[1].face_count;
  const std::uint32_t f2 = w.meshes[2].face_count;
  EXPECT_EQ(plan_pair_chunks(w.mesh_pairs, w.meshes, 2, &gpu::MeshInfo::face_count),
            (std::vector<PairChunk>{{0, 2, f0, std::max(f1, f2)}, {2, 1, f1, f2}}));
  EXPECT_EQ(plan_pair_chunks(w.mesh_pairs, w.meshes, 64, &gpu::MeshInfo::box_face_count),
            (std::vector<PairChunk>{
                {0, 3, std::max(w.meshes[0].box_face_count, w.meshes[1].box_face_count),
                 std::max(w.meshes[1].box_face_count, w.meshes[2].box_face_count)}}));
  EXPECT_TRUE(plan_pair_chunks({}, w.meshes, 1, &gpu::MeshInfo::face_count).empty());
  EXPECT_THROW((void)plan_pair_chunks(w.mesh_pairs, w.meshes, 0, &gpu::MeshInfo::face_count),
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
                        "mesh pairs 2 to 2"),
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
