// The BVH over a body's faces: its shape, its refit, and queries that find exactly the faces
// whose boxes overlap.

#include "core/collision/bvh.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "deformcd/body.h"
#include "support/world_fixtures.h"

namespace deformcd::collision {
namespace {

WorldState two_grids() {
  BodyInit a;
  a.body = build_body(test::tet_grid(6, 5, 4, 0.2, glm::dvec3(0.0)));
  BodyInit b;
  b.body = build_body(test::tet_grid(3, 3, 3, 0.3, glm::dvec3(0.5, 0.3, 0.2)));
  return assemble_world({a, b});
}

TEST(Bvh, EveryFaceIsOneLeafAndNodesAreInPreorder) {
  const WorldState w = two_grids();
  ASSERT_EQ(w.body_bvhs.size(), 2u);
  std::uint32_t offset = 0;
  for (std::size_t b = 0; b < 2; ++b) {
    const gpu::ObjectInfo& o = w.objects[b];
    const gpu::BodyBvh& t = w.body_bvhs[b];
    EXPECT_EQ(t.root, offset);
    EXPECT_EQ(t.node_count, 2 * o.face_count - 1);
    std::multiset<std::uint32_t> leaves;
    for (std::uint32_t i = t.root; i < t.root + t.node_count; ++i) {
      const gpu::BvhNode& n = w.bvh_nodes[i];
      if (i == t.root) {
        EXPECT_EQ(n.parent, gpu::kBvhInternal);
      } else {
        EXPECT_LT(n.parent, i);  // preorder: parents first
        const gpu::BvhNode& p = w.bvh_nodes[n.parent];
        EXPECT_TRUE(p.left == i || p.right == i);
      }
      if (n.face != gpu::kBvhInternal) {
        leaves.insert(n.face);
        EXPECT_EQ(n.left, gpu::kBvhInternal);
      } else {
        EXPECT_EQ(n.left, i + 1);
        EXPECT_GT(n.right, n.left);
        EXPECT_LT(n.right, t.root + t.node_count);
      }
    }
    EXPECT_EQ(leaves.size(), o.face_count);
    EXPECT_EQ(std::set<std::uint32_t>(leaves.begin(), leaves.end()).size(), o.face_count);
    EXPECT_EQ(*leaves.begin(), o.face_offset);
    // A median split: balanced.
    EXPECT_LE(t.depth, static_cast<std::uint32_t>(std::ceil(std::log2(o.face_count))) + 1);
    offset += t.node_count;
  }
}

TEST(Bvh, QueriesFindExactlyTheFacesWhoseBoxesOverlap) {
  WorldState w = two_grids();
  // Deform: the refit must follow.
  for (std::size_t i = 0; i < w.positions.size(); ++i) {
    const glm::vec3 p(w.positions[i]);
    w.positions[i] = glm::vec4(
        p + 0.05f * glm::vec3(std::sin(7.0f * p.y), std::cos(5.0f * p.z), std::sin(3.0f * p.x)),
        w.positions[i].w);
  }
  std::vector<gpu::Box> boxes(w.bvh_nodes.size());
  for (const gpu::BodyBvh& t : w.body_bvhs) {
    refit_bvh(w.bvh_nodes, t.root, t.node_count, w.positions, w.faces, boxes);
  }
  const auto face_box = [&](std::uint32_t f) {
    gpu::Box b = empty_box();
    for (std::uint32_t n : {w.faces[f].a, w.faces[f].b, w.faces[f].c})
      grow_box(b, glm::vec3(w.positions[n]));
    return b;
  };
  const gpu::ObjectInfo& a = w.objects[0];
  const gpu::ObjectInfo& b = w.objects[1];
  std::size_t found_pairs = 0;
  for (std::uint32_t fa = a.face_offset; fa < a.face_offset + a.face_count; ++fa) {
    const gpu::Box q = face_box(fa);
    std::set<std::uint32_t> expected;
    for (std::uint32_t fb = b.face_offset; fb < b.face_offset + b.face_count; ++fb) {
      if (boxes_overlap(q, face_box(fb))) expected.insert(fb);
    }
    std::set<std::uint32_t> found;
    query_bvh(w.bvh_nodes.data(), boxes.data(), w.body_bvhs[1].root, q,
              [&](std::uint32_t f) { EXPECT_TRUE(found.insert(f).second) << "twice: " << f; });
    ASSERT_EQ(found, expected) << "face " << fa;
    found_pairs += found.size();
  }
  EXPECT_GT(found_pairs, 100u);
}

TEST(Bvh, AreaRatioGrowsWhenTheTreeLoosens) {
  WorldState w = two_grids();
  const gpu::BodyBvh& t = w.body_bvhs[0];
  std::vector<gpu::Box> boxes(w.bvh_nodes.size());
  refit_bvh(w.bvh_nodes, t.root, t.node_count, w.positions, w.faces, boxes);
  const double fresh = bvh_area_ratio(w.bvh_nodes, t.root, t.node_count, boxes);
  EXPECT_GT(fresh, 1.0);
  // Mirror the body through its centre plane x = 0.6: siblings now overlap everywhere.
  for (std::uint32_t i = 0; i < w.objects[0].node_count; ++i) {
    glm::vec4& p = w.positions[i];
    p.x = p.y < 0.5f ? 1.2f - p.x : p.x;
  }
  refit_bvh(w.bvh_nodes, t.root, t.node_count, w.positions, w.faces, boxes);
  EXPECT_GT(bvh_area_ratio(w.bvh_nodes, t.root, t.node_count, boxes), 1.2 * fresh);
}

}  // namespace
}  // namespace deformcd::collision
