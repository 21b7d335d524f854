#pragma once
// Narrow phase: exact-shape triangle-triangle intersection after Moller 1997 ("A Fast
// Triangle-Triangle Intersection Test", the interval-overlap method), in float, with tolerances
// relative to the triangles' size so the answer does not depend on the units or on where the
// pair sits in space. Written so that shaders/ can mirror it line for line in GLSL 4.30: no
// recursion, no containers, no exceptions, fixed-size arrays only.

#include <glm/vec3.hpp>

namespace deformcd::collision {

/// Relative tolerance of the "uncertain zone": a vertex whose signed distance to the other
/// triangle's plane is below kTriTriTolerance x (own longest edge)^2 x (pair's longest edge),
/// as the unnormalised dot(cross(e1, e2), q - p0), is taken to lie on that plane; the same
/// tolerance (x longest edge^2) snaps 2D orientations in the coplanar case and (x |line
/// direction| x longest edge) closes gaps between the two intervals on the line. Touching
/// therefore counts as intersecting.
inline constexpr float kTriTriTolerance = 1e-5f;

/// A triangle whose area is below kTriTriDegenerateTolerance x (longest edge)^2 / 2 has no
/// usable plane: it is reported as not intersecting anything (never NaN).
inline constexpr float kTriTriDegenerateTolerance = 1e-6f;

/// Result of tri_tri_intersect. segment is set only when intersect && !coplanar (both ends
/// equal when the triangles touch at a point); otherwise it is zero.
struct TriTriResult {
  bool intersect = false;
  bool coplanar = false;
  glm::vec3 segment[2] = {glm::vec3(0.0f), glm::vec3(0.0f)};
};

/// Intersection of triangles p and q. Symmetric: tri_tri_intersect(p, q) and
/// tri_tri_intersect(q, p) return the same result, segment included.
TriTriResult tri_tri_intersect(const glm::vec3 p[3], const glm::vec3 q[3]);

}  // namespace deformcd::collision
