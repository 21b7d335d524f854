// The BVH over a body's faces: its shape, its refit, and queries that find exactly the faces
// whose boxes overlap.

#include "core/collision/bvh.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "deformcd/body.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::collision {
namespace {

// Two meshes (the grids' surfaces), their trees built on these positions.
test::CollisionFixture two_grids() {
  BodyInit a;
  a.body = build_body(test::tet_grid(6, 5, 4, 0.2, glm::dvec3(0.0)));
  BodyInit b;
  b.body = build_body(test::tet_grid(3, 3, 3, 0.3, glm::dvec3(0.5, 0.3, 0.2)));
  return test::collision_fixture({a, b});
}

TEST(Bvh, EveryFaceIsOneLeafAndNodesAreInPreorder) {
  const test::CollisionFixture fixture = two_grids();
  const CollisionData& w = fixture.data;
  ASSERT_EQ(w.mesh_bvhs.size(), 2u);
  std::uint32_t offset = 0;
  for (std::size_t b = 0; b < 2; ++b) {
    const gpu::MeshInfo& o = w.meshes[b];
    const gpu::BodyBvh& t = w.mesh_bvhs[b];
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
  test::CollisionFixture fixture = two_grids();
  const CollisionData& w = fixture.data;
  // Deform: the refit must follow.
  for (std::vector<glm::vec4>& mesh : fixture.positions) {
    for (glm::vec4& v : mesh) {
      const glm::vec3 p(v);
      v = glm::vec4(
          p + 0.05f * glm::vec3(std::sin(7.0f * p.y), std::cos(5.0f * p.z), std::sin(3.0f * p.x)),
          v.w);
    }
  }
  const VertexPositions positions = fixture.vertices();
  std::vector<gpu::Box> boxes(w.bvh_nodes.size());
  for (const gpu::BodyBvh& t : w.mesh_bvhs) {
    refit_bvh(w.bvh_nodes, t.root, t.node_count, positions, w.faces, boxes);
  }
  const auto face_box = [&](std::uint32_t f) {
    gpu::Box b = empty_box();
    const gpu::Face& face = w.faces[f];
    for (std::uint32_t n : {face.a, face.b, face.c})
      grow_box(b, vertex_position(positions, face.body, n));
    return b;
  };
  const gpu::MeshInfo& a = w.meshes[0];
  const gpu::MeshInfo& b = w.meshes[1];
  std::size_t found_pairs = 0;
  for (std::uint32_t fa = a.face_offset; fa < a.face_offset + a.face_count; ++fa) {
    const gpu::Box q = face_box(fa);
    std::set<std::uint32_t> expected;
    for (std::uint32_t fb = b.face_offset; fb < b.face_offset + b.face_count; ++fb) {
      if (boxes_overlap(q, face_box(fb))) expected.insert(fb);
    }
    std::set<std::uint32_t> found;
    query_bvh(w.bvh_nodes.data(), boxes.data(), w.mesh_bvhs[1].root, q,
              [&](std::uint32_t f) { EXPECT_TRUE(found.insert(f).second) << "twice: " << f; });
    ASSERT_EQ(found, expected) << "face " << fa;
    found_pairs += found.size();
  }
  EXPECT_GT(found_pairs, 100u);
}

TEST(Bvh, AreaRatioGrowsWhenTheTreeLoosens) {
  test::CollisionFixture fixture = two_grids();
  const CollisionData& w = fixture.data;
  const gpu::BodyBvh& t = w.mesh_bvhs[0];
  std::vector<gpu::Box> boxes(w.bvh_nodes.size());
  refit_bvh(w.bvh_nodes, t.root, t.node_count, fixture.vertices(), w.faces, boxes);
  const double fresh = bvh_area_ratio(w.bvh_nodes, t.root, t.node_count, boxes);
  EXPECT_GT(fresh, 1.0);
  // Mirror the lower half of mesh 0 through its centre plane x = 0.6 (in place: the views
  // still point at the arrays): siblings now overlap everywhere.
  for (glm::vec4& p : fixture.positions[0])
    p.x = p.y < 0.5f ? 1.2f - p.x : p.x;
  refit_bvh(w.bvh_nodes, t.root, t.node_count, fixture.vertices(), w.faces, boxes);
  EXPECT_GT(bvh_area_ratio(w.bvh_nodes, t.root, t.node_count, boxes), 1.2 * fresh);
}

TEST(Bvh, ACutHoldsEveryNodeOnceAndItsSubtreesAreWholeAndSmall) {
  const test::CollisionFixture fixture = two_grids();
  const CollisionData& w = fixture.data;
  for (const gpu::BodyBvh& t : w.mesh_bvhs) {
    for (std::uint32_t max_nodes : {1u, 16u, 100u, t.node_count}) {
      const BvhCut cut = cut_bvh(w.bvh_nodes, t.root, t.node_count, max_nodes);
      std::vector<int> seen(t.node_count, 0);
      for (std::uint32_t node : cut.top) {
        EXPECT_EQ(w.bvh_nodes[node].face, gpu::kBvhInternal);
        ++seen[node - t.root];
      }
      EXPECT_TRUE(std::is_sorted(cut.top.begin(), cut.top.end()));  // preorder
      std::uint32_t previous = 0;
      for (const glm::uvec2& s : cut.subtrees) {
        EXPECT_TRUE(s.y <= max_nodes || s.y == 1u);
        EXPECT_GE(s.x, previous);
        previous = s.x + s.y;
        // A whole subtree: its root's parent is above the cut, and its nodes' parents inside it.
        if (s.x != t.root) {
          EXPECT_EQ(seen[w.bvh_nodes[s.x].parent - t.root], 1);
        }
        for (std::uint32_t i = s.x; i < s.x + s.y; ++i) {
          ++seen[i - t.root];
          if (i != s.x) {
            EXPECT_TRUE(w.bvh_nodes[i].parent >= s.x && w.bvh_nodes[i].parent < i);
          }
        }
      }
      EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }))
          << "max " << max_nodes;
      if (max_nodes >= t.node_count) {
        EXPECT_TRUE(cut.top.empty());
      }
    }
  }
}

TEST(Bvh, AreaRatioIsTheInternalAreaOverTheRoot) {
  const test::CollisionFixture fixture = two_grids();
  const CollisionData& w = fixture.data;
  std::vector<gpu::Box> boxes(w.bvh_nodes.size());
  for (const gpu::BodyBvh& t : w.mesh_bvhs) {
    refit_bvh(w.bvh_nodes, t.root, t.node_count, fixture.vertices(), w.faces, boxes);
    double internal = 0.0;
    for (std::uint32_t i = t.root; i < t.root + t.node_count; ++i) {
      if (w.bvh_nodes[i].face == gpu::kBvhInternal) internal += box_area(boxes[i]);
    }
    EXPECT_NEAR(bvh_area_ratio(w.bvh_nodes, t.root, t.node_count, boxes),
                internal / box_area(boxes[t.root]), 1e-12 * internal / box_area(boxes[t.root]));
  }
}

}  // namespace
}  // namespace deformcd::collision
