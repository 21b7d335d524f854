#pragma once
// Narrow phase: exact-shape triangle-triangle intersection after Moller 1997 ("A Fast
// Triangle-Triangle Intersection Test", the interval-overlap method), in float, with tolerances
// relative to the triangles' size so the answer does not depend on the units or on where the
// pair sits in space. Written so that shaders/ can mirror it line for line in GLSL 4.30: no
// recursion, no containers, no exceptions, fixed-size arrays only.

#include <glm/vec3.hpp>

namespace deformcd::collision {

/// Relative tolerance of the "uncertain zone" (see the .cpp for the why). A vertex x of one
/// triangle whose distance to the other triangle's plane (normal n, longest edge L, vertex a0)
/// is below (kTriTriTolerance + kTriTriRoundoff x L^2 / |n|) x S, S the pair's longest edge, is
/// taken to lie on that plane: |dot(n, x - a0)| <= kTriTriTolerance |n| S + kTriTriRoundoff L^2 S.
/// The same kTriTriTolerance x S^2 snaps 2D orientations in the coplanar case, and x S closes
/// gaps between the two intervals on the planes' line. Touching counts as intersecting, and
/// "apart" is answered only beyond the tolerance: a pair of proper triangles that meets exactly
/// on the float coordinates is never reported apart (a gap found on the planes' line is
/// confirmed by a test that constructs no crossing of the planes, see the .cpp).
inline constexpr float kTriTriTolerance = 1e-5f;

/// Rounding term of the plane tolerance, about 8 float ulps of L^2 S: the error of the float
/// plane distance, which does not shrink with |n| and so dominates for slivers.
inline constexpr float kTriTriRoundoff = 1e-6f;

/// A triangle with |cross(e1, e2)| <= kTriTriDegenerateTolerance x L^2 (height below ~1e-4 of
/// its longest edge) has no plane that float can pin down: it is reported as not intersecting
/// anything, never NaN. Its neighbours in a closed surface still report the contact.
inline constexpr float kTriTriDegenerateTolerance = 1e-4f;

/// Result of tri_tri_intersect. segment is set only when intersect && !coplanar (both ends
/// equal when the triangles touch at a point); otherwise it is zero. coplanar is only
/// determined for pairs not rejected first: bounding boxes apart, or one triangle (the second in
/// the pair's canonical order) wholly on one side of the other's plane beyond the tolerance.
struct TriTriResult {
  bool intersect = false;
  bool coplanar = false;
  glm::vec3 segment[2] = {glm::vec3(0.0f), glm::vec3(0.0f)};
};

/// Intersection of triangles p and q. Symmetric: tri_tri_intersect(p, q) and
/// tri_tri_intersect(q, p) return the same result, segment included.
TriTriResult tri_tri_intersect(const glm::vec3 p[3], const glm::vec3 q[3]);

/// What tri_tri_intersect computes of each triangle on its own, by the same float operations.
/// A caller that tests one triangle against several (a broad phase's candidates: about three
/// tests per face in contact on bench_peers' frames) makes it once per triangle and pass.
struct TriangleGeometry {
  glm::vec3 v[3];
  glm::vec3 n;    ///< cross(v[1] - v[0], v[2] - v[0])
  glm::vec3 u;    ///< n / |n|, zero for a degenerate triangle
  float l2;       ///< the longest edge, squared
  float n_len;    ///< |n|
  float edge;     ///< sqrt(l2)
  float rel_tol;  ///< kTriTriTolerance + kTriTriRoundoff x l2 / |n|: the plane tolerance / size
  bool proper;    ///< not degenerate: |n| > kTriTriDegenerateTolerance x l2
};

/// The geometry of triangle t (vertices in the order given).
TriangleGeometry triangle_geometry(const glm::vec3 t[3]);

/// tri_tri_intersect(p.v, q.v), bit for bit, from the triangles' geometry.
TriTriResult tri_tri_intersect(const TriangleGeometry& p, const TriangleGeometry& q);

/// The same for triangles whose bounding boxes are known to touch (detail::boxes_touch, as a
/// BVH's leaf boxes, the min/max of the same floats, are when they overlap): its first test
/// skipped.
TriTriResult tri_tri_intersect_touching(const TriangleGeometry& p, const TriangleGeometry& q);

}  // namespace deformcd::collision
