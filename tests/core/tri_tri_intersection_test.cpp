#include "core/collision/tri_tri_intersection.h"

#include <cmath>
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "core/collision/tri_tri_primitives.h"

namespace deformcd::collision {
namespace {

using glm::vec3;

struct Tri {
  vec3 v[3];
};

// The base triangle of most cases: right triangle in z = 0, legs of length 2.
const Tri kBase{{vec3(0, 0, 0), vec3(2, 0, 0), vec3(0, 2, 0)}};
// Crosses kBase: lies in y = 0.5 and meets z = 0 along x in [0, 2]; with kBase's x in [0, 1.5]
// at y = 0.5 the intersection is the segment (0, 0.5, 0)-(1.5, 0.5, 0).
const Tri kCrossing{{vec3(-1, 0.5f, -1), vec3(3, 0.5f, -1), vec3(1, 0.5f, 1)}};

TriTriResult intersect(const Tri& p, const Tri& q) {
  return tri_tri_intersect(p.v, q.v);
}

Tri transformed(const Tri& t, float scale, const vec3& offset) {
  return Tri{{t.v[0] * scale + offset, t.v[1] * scale + offset, t.v[2] * scale + offset}};
}

bool is_finite(const vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The segment's ends match {a, b} in either order, within tol.
void expect_segment(const TriTriResult& r, const vec3& a, const vec3& b, float tol) {
  const bool forward = glm::length(r.segment[0] - a) <= tol && glm::length(r.segment[1] - b) <= tol;
  const bool backward =
      glm::length(r.segment[0] - b) <= tol && glm::length(r.segment[1] - a) <= tol;
  EXPECT_TRUE(forward || backward)
      << "segment (" << r.segment[0].x << ", " << r.segment[0].y << ", " << r.segment[0].z
      << ") - (" << r.segment[1].x << ", " << r.segment[1].y << ", " << r.segment[1].z << ")";
}

TEST(TriTriIntersect, SeparatedByAPlaneDoNotIntersect) {
  const Tri above{{vec3(0, 0, 0.5f), vec3(1, 0, 1), vec3(0, 1, 2)}};
  const TriTriResult r = intersect(kBase, above);
  EXPECT_FALSE(r.intersect);
  EXPECT_FALSE(r.coplanar);
  // Planes cross, but the triangles miss each other on the line: q's interval is beyond p's.
  const Tri beside{{vec3(3, 3, -1), vec3(4, 3, -1), vec3(3.5f, 3, 1)}};
  EXPECT_FALSE(intersect(kBase, beside).intersect);
}

TEST(TriTriIntersect, CrossingGivesTheHandComputedSegment) {
  const TriTriResult r = intersect(kBase, kCrossing);
  ASSERT_TRUE(r.intersect);
  EXPECT_FALSE(r.coplanar);
  expect_segment(r, vec3(0, 0.5f, 0), vec3(1.5f, 0.5f, 0), 1e-6f);
}

TEST(TriTriIntersect, TouchingAtAVertexIntersectsAtThatPoint) {
  const Tri q{{vec3(0.5f, 0.5f, 0), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)}};
  const TriTriResult r = intersect(kBase, q);
  ASSERT_TRUE(r.intersect);
  EXPECT_FALSE(r.coplanar);
  expect_segment(r, vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0), 1e-6f);
}

TEST(TriTriIntersect, TouchingAlongAnEdgeGivesThatEdge) {
  const Tri q{{vec3(0.2f, 0.2f, 0), vec3(1, 0.2f, 0), vec3(0.5f, 0.5f, 1)}};
  const TriTriResult r = intersect(kBase, q);
  ASSERT_TRUE(r.intersect);
  EXPECT_FALSE(r.coplanar);
  expect_segment(r, vec3(0.2f, 0.2f, 0), vec3(1, 0.2f, 0), 1e-6f);
}

// Rotates about the y axis by 30 degrees: kBase then spans z, so that a triangle hovering
// above it has a bounding box overlapping kBase's and reaches the plane test.
Tri tilted(const Tri& t) {
  const float c = std::cos(0.5236f);
  const float s = std::sin(0.5236f);
  Tri out;
  for (int i = 0; i < 3; ++i) {
    out.v[i] = vec3(c * t.v[i].x + s * t.v[i].z, t.v[i].y, -s * t.v[i].x + c * t.v[i].z);
  }
  return out;
}

TEST(TriTriIntersect, NearTouchingIsDecidedRelativeToSize) {
  // A vertex 2e-6 (relative to the size, 2) above kBase, over its inside: in the uncertain zone,
  // decided as touching, hence intersecting, at any scale.
  const Tri barely{{vec3(0.5f, 0.5f, 4e-6f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)}};
  // 1e-3 above the plane: clearly apart, at any scale.
  const Tri apart{{vec3(0.5f, 0.5f, 2e-3f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)}};
  for (float scale : {1e-6f, 1.0f, 1e3f}) {
    const Tri base = tilted(transformed(kBase, scale, vec3(0)));
    EXPECT_TRUE(intersect(base, tilted(transformed(barely, scale, vec3(0)))).intersect) << scale;
    EXPECT_FALSE(intersect(base, tilted(transformed(apart, scale, vec3(0)))).intersect) << scale;
  }
}

TEST(TriTriIntersect, BoundingBoxesApartNeverIntersect) {
  // Untilted, `barely` hovers above kBase's plane with its bounding box apart from kBase's in z:
  // decided exactly (no contact), whatever the plane tolerance would say.
  const Tri barely{{vec3(0.5f, 0.5f, 4e-6f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)}};
  EXPECT_FALSE(intersect(kBase, barely).intersect);
  // Touching bounding boxes (the vertex on the plane) still reach the test, and touch.
  const Tri touching{{vec3(0.5f, 0.5f, 0.0f), vec3(1, 0.5f, 1), vec3(0.5f, 1, 1)}};
  EXPECT_TRUE(intersect(kBase, touching).intersect);
}

TEST(TriTriIntersect, ThinTrianglesCrossUntilTooThinForAPlane) {
  // kCrossing flattened to a height of 2e-2 (5e-3 of its length^2 in area), still straddling
  // z = 0 with the same crossings x = 0 and x = 2: the same segment as kCrossing.
  const float h = 1e-2f;
  const Tri thin{{vec3(-1, 0.5f, -h), vec3(3, 0.5f, -h), vec3(1, 0.5f, h)}};
  const TriTriResult r = intersect(kBase, thin);
  ASSERT_TRUE(r.intersect);
  expect_segment(r, vec3(0, 0.5f, 0), vec3(1.5f, 0.5f, 0), 1e-5f);
  // Height 1e-6 of the length: below kTriTriDegenerateTolerance, reported as no intersection.
  const Tri sliver{{vec3(-1, 0.5f, -1e-6f), vec3(3, 0.5f, -1e-6f), vec3(1, 0.5f, 1e-6f)}};
  EXPECT_FALSE(intersect(kBase, sliver).intersect);
}

TEST(TriTriIntersect, CoplanarOverlappingIntersect) {
  const Tri q{{vec3(0.5f, 0.5f, 0), vec3(3, 0.5f, 0), vec3(0.5f, 3, 0)}};
  const TriTriResult r = intersect(kBase, q);
  EXPECT_TRUE(r.intersect);
  EXPECT_TRUE(r.coplanar);
  EXPECT_EQ(r.segment[0], vec3(0));
  EXPECT_EQ(r.segment[1], vec3(0));
}

TEST(TriTriIntersect, CoplanarDisjointDoNotIntersect) {
  // Bounding boxes apart: rejected before the planes are looked at.
  const Tri far{{vec3(3, 3, 0), vec3(5, 3, 0), vec3(3, 5, 0)}};
  EXPECT_FALSE(intersect(kBase, far).intersect);
  // Just across kBase's hypotenuse (x + y = 2), with a winding opposite to kBase's.
  const Tri across{{vec3(1.1f, 1.1f, 0), vec3(1.1f, 3, 0), vec3(3, 1.1f, 0)}};
  EXPECT_FALSE(intersect(kBase, across).intersect);
}

TEST(TriTriIntersect, CoplanarOneInsideTheOtherIntersect) {
  const Tri inner{{vec3(0.2f, 0.2f, 0), vec3(0.6f, 0.2f, 0), vec3(0.2f, 0.6f, 0)}};
  EXPECT_TRUE(intersect(kBase, inner).intersect);
  EXPECT_TRUE(intersect(inner, kBase).intersect);
  // Tilted plane, so the projection is not trivially z = 0.
  const Tri tilted_outer{{vec3(0, 0, 0), vec3(4, 0, 4), vec3(0, 4, 0)}};
  const Tri tilted_inner{{vec3(1, 1, 1), vec3(1.5f, 1, 1.5f), vec3(1, 1.5f, 1)}};
  const TriTriResult r = intersect(tilted_inner, tilted_outer);
  EXPECT_TRUE(r.intersect);
  EXPECT_TRUE(r.coplanar);
}

TEST(TriTriIntersect, DegenerateTrianglesNeverIntersectAndNeverGiveNaN) {
  const Tri collinear{{vec3(-1, 0.5f, -1), vec3(0, 0.5f, 0), vec3(1, 0.5f, 1)}};
  const Tri point{{vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0), vec3(0.5f, 0.5f, 0)}};
  for (const Tri& degenerate : {collinear, point}) {
    for (const TriTriResult& r : {intersect(kBase, degenerate), intersect(degenerate, kBase),
                                  intersect(degenerate, degenerate)}) {
      EXPECT_FALSE(r.intersect);
      EXPECT_FALSE(r.coplanar);
      EXPECT_TRUE(is_finite(r.segment[0]) && is_finite(r.segment[1]));
    }
  }
}

TEST(TriTriIntersect, CrossingAnswerDoesNotDependOnScaleOrPosition) {
  struct Frame {
    float scale;
    vec3 offset;
  };
  for (const Frame& f : {Frame{1e-3f, vec3(0)}, Frame{1e3f, vec3(0)}, Frame{1e-6f, vec3(0)},
                         Frame{1.0f, vec3(1e3f, -1e3f, 1e3f)}}) {
    const TriTriResult r =
        intersect(transformed(kBase, f.scale, f.offset), transformed(kCrossing, f.scale, f.offset));
    ASSERT_TRUE(r.intersect) << f.scale;
    EXPECT_FALSE(r.coplanar);
    // Error budget: a few ulps of the size and of the coordinates' magnitude.
    const float tol = 1e-6f * f.scale + 4e-7f * glm::length(f.offset);
    expect_segment(r, vec3(0, 0.5f, 0) * f.scale + f.offset,
                   vec3(1.5f, 0.5f, 0) * f.scale + f.offset, tol);
  }
}

TEST(TriTriIntersect, IsSymmetricInItsArguments) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  int intersecting = 0;
  for (int n = 0; n < 5000; ++n) {
    Tri p;
    Tri q;
    for (int i = 0; i < 3; ++i) {
      p.v[i] = vec3(coord(rng), coord(rng), coord(rng));
      q.v[i] = vec3(coord(rng), coord(rng), coord(rng));
    }
    const TriTriResult pq = intersect(p, q);
    const TriTriResult qp = intersect(q, p);
    ASSERT_EQ(pq.intersect, qp.intersect) << n;
    ASSERT_EQ(pq.coplanar, qp.coplanar) << n;
    ASSERT_EQ(pq.segment[0], qp.segment[0]) << n;
    ASSERT_EQ(pq.segment[1], qp.segment[1]) << n;
    intersecting += pq.intersect ? 1 : 0;
  }
  EXPECT_GT(intersecting, 500);  // the sample exercises both answers
  EXPECT_LT(intersecting, 4500);
}

// The entry the CPU broad phases use (each triangle's geometry made once per pass) gives the
// plain test's result bit for bit: random pairs, coplanar ones, degenerate ones, both orders.
TEST(TriTriIntersect, FromTriangleGeometryGivesTheSameBits) {
  std::mt19937 rng(271828);
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  const auto same = [](const vec3& x, const vec3& y) {
    return std::memcmp(&x, &y, sizeof(vec3)) == 0;
  };
  int intersecting = 0;
  for (int n = 0; n < 20000; ++n) {
    Tri p;
    Tri q;
    for (int i = 0; i < 3; ++i) {
      p.v[i] = vec3(coord(rng), coord(rng), coord(rng));
      q.v[i] = vec3(coord(rng), coord(rng), coord(rng));
    }
    if (n % 4 == 1) {  // coplanar: both in z = p's first z
      for (int i = 0; i < 3; ++i)
        q.v[i].z = p.v[i].z = p.v[0].z;
    } else if (n % 4 == 2) {  // p degenerate (its third vertex on its first edge) or nearly
      p.v[2] = p.v[0] + (p.v[1] - p.v[0]) * 0.25f + vec3(0.0f, 0.0f, n % 8 == 2 ? 0.0f : 1e-5f);
    } else if (n % 4 == 3) {  // q shares p's vertex 0 and nearly its plane
      q.v[0] = p.v[0];
    }
    for (int order = 0; order < 2; ++order) {
      const Tri& a = order == 0 ? p : q;
      const Tri& b = order == 0 ? q : p;
      const TriTriResult plain = intersect(a, b);
      const TriTriResult prepared =
          tri_tri_intersect(triangle_geometry(a.v), triangle_geometry(b.v));
      ASSERT_EQ(plain.intersect, prepared.intersect) << n;
      ASSERT_EQ(plain.coplanar, prepared.coplanar) << n;
      ASSERT_TRUE(same(plain.segment[0], prepared.segment[0])) << n;
      ASSERT_TRUE(same(plain.segment[1], prepared.segment[1])) << n;
      if (detail::boxes_touch(a.v, b.v)) {  // the bvh's entry, for boxes known to touch
        const TriTriResult touching =
            tri_tri_intersect_touching(triangle_geometry(a.v), triangle_geometry(b.v));
        ASSERT_EQ(plain.intersect, touching.intersect) << n;
        ASSERT_EQ(plain.coplanar, touching.coplanar) << n;
        ASSERT_TRUE(same(plain.segment[0], touching.segment[0])) << n;
        ASSERT_TRUE(same(plain.segment[1], touching.segment[1])) << n;
      }
      intersecting += plain.intersect ? 1 : 0;
    }
  }
  EXPECT_GT(intersecting, 4000);
}

}  // namespace
}  // namespace deformcd::collision
