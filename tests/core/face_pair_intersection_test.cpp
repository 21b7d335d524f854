// The narrow phase of face pairs that share nodes (self-collision): edge neighbours are never a
// contact, faces sharing one node are a contact only when they meet somewhere else too, and
// faces sharing nothing keep the plain triangle test.

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "core/collision/face_pair_intersection.h"

namespace deformcd::collision {
namespace {

using glm::vec3;

struct Tri {
  std::array<vec3, 3> v;
};

// Triangles p and q sharing their first vertex.
TriTriResult sharing(const Tri& p, const Tri& q) {
  return tri_tri_intersect_sharing_vertex(p.v.data(), q.v.data());
}

Tri scaled(const Tri& t, float s, const vec3& shift = vec3(0.0f)) {
  return {{t.v[0] * s + shift, t.v[1] * s + shift, t.v[2] * s + shift}};
}

TEST(SharedNodes, CountsCommonNodesAndTheirCorners) {
  const gpu::Face f{10, 11, 12, 0};
  EXPECT_EQ(shared_nodes(f, {20, 21, 22, 0}).count, 0);
  const SharedNodes one = shared_nodes(f, {20, 12, 22, 0});
  EXPECT_EQ(one.count, 1);
  EXPECT_EQ(one.corner_a, 2);
  EXPECT_EQ(one.corner_b, 1);
  EXPECT_EQ(shared_nodes(f, {11, 10, 22, 0}).count, 2);
  EXPECT_EQ(shared_nodes(f, {12, 10, 11, 0}).count, 3);
}

TEST(SharedNodes, FacesOfDifferentMeshesShareNoNodeWhateverTheirIndices) {
  // Vertex indices are local to each mesh: the same numbers in two meshes are two vertices.
  const gpu::Face f{10, 11, 12, 0};
  EXPECT_EQ(shared_nodes(f, {20, 12, 22, 1}).count, 0);
  EXPECT_EQ(shared_nodes(f, {11, 10, 22, 1}).count, 0);
  EXPECT_EQ(shared_nodes(f, {10, 11, 12, 1}).count, 0);
  EXPECT_EQ(shared_nodes({10, 11, 12, 3}, {12, 10, 11, 2}).count, 0);
}

TEST(SegmentTriangle, CrossingTouchingInPlaneAndApart) {
  const vec3 t[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0)};
  EXPECT_TRUE(segment_triangle_meet(vec3(0.2f, 0.2f, -1), vec3(0.2f, 0.2f, 1), t));
  EXPECT_FALSE(segment_triangle_meet(vec3(0.8f, 0.8f, -1), vec3(0.8f, 0.8f, 1), t));
  EXPECT_FALSE(segment_triangle_meet(vec3(0.2f, 0.2f, 0.1f), vec3(0.2f, 0.2f, 1), t));
  EXPECT_TRUE(segment_triangle_meet(vec3(0.2f, 0.2f, 0), vec3(0.2f, 0.2f, 1), t));  // an end on t
  // In t's plane: through it, wholly inside, and beside it.
  EXPECT_TRUE(segment_triangle_meet(vec3(-1, 0.3f, 0), vec3(2, 0.3f, 0), t));
  EXPECT_TRUE(segment_triangle_meet(vec3(0.1f, 0.1f, 0), vec3(0.2f, 0.3f, 0), t));
  EXPECT_FALSE(segment_triangle_meet(vec3(0.6f, 0.6f, 0), vec3(2, 0.6f, 0), t));
  // A degenerate triangle meets nothing.
  const vec3 sliver[3] = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(2, 0, 0)};
  EXPECT_FALSE(segment_triangle_meet(vec3(0.5f, -1, 0), vec3(0.5f, 1, 0), sliver));
}

// A fan around vertex v = 0 in the plane z = 0: triangles (v, r(a0), r(a1)), r(a) at angle a.
Tri fan_triangle(float a0_deg, float a1_deg, float tilt_z = 0.0f) {
  const float a0 = glm::radians(a0_deg);
  const float a1 = glm::radians(a1_deg);
  return {{vec3(0.0f), vec3(std::cos(a0), std::sin(a0), tilt_z),
           vec3(std::cos(a1), std::sin(a1), tilt_z)}};
}

TEST(SharingVertex, FlatFanNeighboursAcrossTheVertexDoNotCollide) {
  // Faces of one flat vertex ring, sharing only the vertex (the ring's faces between them):
  // they touch at v and nowhere else, so they are no contact.
  const Tri p = fan_triangle(0, 60);
  for (float start : {120.0f, 180.0f, 240.0f}) {
    EXPECT_FALSE(sharing(p, fan_triangle(start, start + 60)).intersect) << start;
    EXPECT_FALSE(sharing(fan_triangle(start, start + 60), p).intersect) << start;
  }
  // Slightly bent rings, both ways.
  EXPECT_FALSE(sharing(p, fan_triangle(180, 240, 0.05f)).intersect);
  EXPECT_FALSE(sharing(p, fan_triangle(180, 240, -0.05f)).intersect);
}

TEST(SharingVertex, CoplanarOverlappingSectorsCollide) {
  // Folded flat onto each other: sectors 0-60 and 30-90 overlap in 30-60.
  const TriTriResult r = sharing(fan_triangle(0, 60), fan_triangle(30, 90));
  EXPECT_TRUE(r.intersect);
  EXPECT_TRUE(r.coplanar);
  // One sector inside the other, with the opposite edge of neither crossing the other.
  EXPECT_TRUE(sharing(fan_triangle(0, 90), fan_triangle(30, 60)).intersect);
  EXPECT_TRUE(sharing(fan_triangle(30, 60), fan_triangle(0, 90)).intersect);
}

TEST(SharingVertex, PassingThroughCollidesWithASegmentFromTheVertex) {
  // p in z = 0; q leaves v downwards and comes up through p: its opposite edge crosses p.
  const Tri p{{vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)}};
  const Tri q{{vec3(0, 0, 0), vec3(0.5f, 0.5f, 1), vec3(0.5f, 0.5f, -1)}};
  const TriTriResult r = sharing(p, q);
  ASSERT_TRUE(r.intersect);
  EXPECT_FALSE(r.coplanar);
  // The intersection runs from v along the diagonal x = y, to where q's edge crosses z = 0.
  const float ends_at_v = std::min(glm::length(r.segment[0]), glm::length(r.segment[1]));
  const float far_end = std::max(glm::length(r.segment[0]), glm::length(r.segment[1]));
  EXPECT_LT(ends_at_v, 1e-6f);
  EXPECT_NEAR(far_end, std::sqrt(0.5f), 1e-5f);
  const TriTriResult swapped = sharing(q, p);
  EXPECT_TRUE(swapped.intersect);
  EXPECT_EQ(swapped.segment[0], r.segment[0]);
  EXPECT_EQ(swapped.segment[1], r.segment[1]);
}

TEST(SharingVertex, TouchingOnlyAtTheVertexInSpaceDoesNotCollide) {
  const Tri p{{vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)}};
  // q above p, crossing p's plane only at v; and q standing on p's plane outside p's sector.
  EXPECT_FALSE(sharing(p, {{vec3(0, 0, 0), vec3(1, 1, 1), vec3(-1, 1, 2)}}).intersect);
  EXPECT_FALSE(sharing(p, {{vec3(0, 0, 0), vec3(-1, -1, 1), vec3(-1, -1, -1)}}).intersect);
  // q's opposite edge ends exactly on p's plane inside p: touching counts.
  EXPECT_TRUE(sharing(p, {{vec3(0, 0, 0), vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 1)}}).intersect);
}

TEST(SharingVertex, AnswersDoNotDependOnScaleOrPlace) {
  const std::vector<std::array<Tri, 2>> cases = {
      {fan_triangle(0, 60), fan_triangle(180, 240)},
      {fan_triangle(0, 60), fan_triangle(30, 90)},
      {Tri{{vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)}},
       Tri{{vec3(0, 0, 0), vec3(0.5f, 0.5f, 1), vec3(0.5f, 0.5f, -1)}}},
  };
  for (const auto& c : cases) {
    const bool expected = sharing(c[0], c[1]).intersect;
    for (float s : {1e-3f, 1e3f}) {
      EXPECT_EQ(sharing(scaled(c[0], s, vec3(s)), scaled(c[1], s, vec3(s))).intersect, expected)
          << s;
    }
  }
}

// face_pair_intersect picks the test from the faces' nodes.
class FacePairTest : public ::testing::Test {
 protected:
  // Two triangles folded onto each other over edge 0-1 (nodes 2 and 3 on the same side), and a
  // third face sharing only node 0 that passes through the first.
  std::vector<glm::vec4> points = {
      {0, 0, 0, 0},        {2, 0, 0, 0}, {1, 1, 0, 0}, {1, 0.5f, 0, 0}, {0.5f, 0.5f, 1, 0},
      {0.5f, 0.5f, -1, 0}, {5, 5, 5, 0}, {6, 5, 5, 0}, {5, 6, 5, 0},
  };
  // One mesh (Face::body 0) whose vertices are `points`.
  const MeshVertices mesh{&points[0].x, 4u};
  const VertexPositions positions = &mesh;
};

TEST_F(FacePairTest, EdgeNeighboursAreNeverAContact) {
  const TriTriResult r = face_pair_intersect({0, 1, 2, 0}, {1, 0, 3, 0}, positions);
  EXPECT_FALSE(r.intersect);
  // The same triangles as separate nodes (different bodies) do overlap.
  const vec3 p[3] = {vec3(0, 0, 0), vec3(2, 0, 0), vec3(1, 1, 0)};
  const vec3 q[3] = {vec3(2, 0, 0), vec3(0, 0, 0), vec3(1, 0.5f, 0)};
  EXPECT_TRUE(tri_tri_intersect(p, q).intersect);
}

TEST_F(FacePairTest, VertexNeighboursAreTestedBeyondTheSharedNodeInAnyCornerOrder) {
  // Node 0 at every corner of both faces: the rotation keeps the answer.
  const std::array<gpu::Face, 3> fa = {{{0, 1, 2, 0}, {2, 0, 1, 0}, {1, 2, 0, 0}}};
  const std::array<gpu::Face, 3> fb = {{{0, 4, 5, 0}, {5, 0, 4, 0}, {4, 5, 0, 0}}};
  for (const gpu::Face& a : fa) {
    for (const gpu::Face& b : fb) {
      EXPECT_TRUE(face_pair_intersect(a, b, positions).intersect);
      EXPECT_TRUE(face_pair_intersect(b, a, positions).intersect);
    }
  }
  // Face (0, 6, 7) shares node 0 and runs away from face (0, 1, 2): no contact, though the
  // plain test would report the shared node.
  EXPECT_FALSE(face_pair_intersect({0, 1, 2, 0}, {0, 6, 7, 0}, positions).intersect);
}

TEST_F(FacePairTest, FacesSharingNothingTakeTheTriangleTest) {
  EXPECT_FALSE(face_pair_intersect({0, 1, 2, 0}, {6, 7, 8, 0}, positions).intersect);
  const TriTriResult r = face_pair_intersect({1, 2, 3, 0}, {4, 5, 6, 0}, positions);
  const vec3 p[3] = {vec3(2, 0, 0), vec3(1, 1, 0), vec3(1, 0.5f, 0)};
  const vec3 q[3] = {vec3(0.5f, 0.5f, 1), vec3(0.5f, 0.5f, -1), vec3(5, 5, 5)};
  EXPECT_EQ(r.intersect, tri_tri_intersect(p, q).intersect);
}

// Faces of two meshes whose local vertex indices coincide take the plain triangle test: the
// pairs below are all contacts, though within one mesh the same indices would make the first
// two edge (or all-node) neighbours and the third vertex neighbours that meet nowhere else.
TEST_F(FacePairTest, FacesOfDifferentMeshesWithTheSameIndicesTakeTheTriangleTest) {
  // Mesh 1: `points` moved by 0.1 within the plane z = 0.
  std::vector<glm::vec4> moved = points;
  for (glm::vec4& p : moved)
    p += glm::vec4(0.1f, 0.1f, 0.0f, 0.0f);
  const MeshVertices same[2] = {mesh, mesh};
  const MeshVertices shifted[2] = {mesh, {&moved[0].x, 4u}};
  struct Case {
    gpu::Face a;
    gpu::Face b;
    const MeshVertices* positions;
  };
  const Case cases[] = {
      // The folded-over pair of EdgeNeighboursAreNeverAContact, as two meshes on one array.
      {{0, 1, 2, 0}, {1, 0, 3, 1}, same},
      // Face (0, 1, 2) against its copy in mesh 1, shifted within its plane: they overlap.
      {{0, 1, 2, 0}, {0, 1, 2, 1}, shifted},
      // Face (0, 6, 7) of mesh 1 touches face (0, 1, 2) of mesh 0 at their coinciding vertex
      // 0 only: a contact between meshes (touching counts), none within one mesh.
      {{0, 1, 2, 0}, {0, 6, 7, 1}, same},
  };
  for (const Case& c : cases) {
    vec3 p[3];
    vec3 q[3];
    face_vertices(c.positions, c.a, p);
    face_vertices(c.positions, c.b, q);
    const TriTriResult expected = tri_tri_intersect(p, q);
    ASSERT_TRUE(expected.intersect) << c.b.a << " " << c.b.b << " " << c.b.c;
    const TriTriResult r = face_pair_intersect(c.a, c.b, c.positions);
    EXPECT_TRUE(r.intersect) << c.b.a << " " << c.b.b << " " << c.b.c;
    EXPECT_EQ(r.coplanar, expected.coplanar);
    EXPECT_EQ(r.segment[0], expected.segment[0]);
    EXPECT_EQ(r.segment[1], expected.segment[1]);
    // Within one mesh the same indices are neighbours: not a contact.
    const gpu::Face b_in_a{c.b.a, c.b.b, c.b.c, 0};
    EXPECT_FALSE(face_pair_intersect(c.a, b_in_a, positions).intersect)
        << c.b.a << " " << c.b.b << " " << c.b.c;
  }
}

}  // namespace
}  // namespace deformcd::collision
