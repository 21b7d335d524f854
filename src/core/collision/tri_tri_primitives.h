#pragma once
// The float building blocks of the narrow phase, shared by the triangle-triangle test and the
// segment-triangle test of faces sharing a vertex (shaders/collision/tri_tri_intersection.glsl
// mirrors them). Internal to src/core/collision.

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/collision/tri_tri_intersection.h"

namespace deformcd::collision::detail {

inline float longest_edge2(const glm::vec3 t[3]) {
  const glm::vec3 e0 = t[1] - t[0];
  const glm::vec3 e1 = t[2] - t[1];
  const glm::vec3 e2 = t[0] - t[2];
  return std::max(glm::dot(e0, e0), std::max(glm::dot(e1, e1), glm::dot(e2, e2)));
}

inline float snap_to_zero(float v, float tolerance) {
  return std::abs(v) <= tolerance ? 0.0f : v;
}

// True when all three values are strictly on one side (a triangle wholly off the plane).
inline bool same_strict_side(const float d[3]) {
  return (d[0] > 0.0f && d[1] > 0.0f && d[2] > 0.0f) || (d[0] < 0.0f && d[1] < 0.0f && d[2] < 0.0f);
}

inline bool same_strict_sign(float a, float b) {
  return (a < 0.0f && b < 0.0f) || (a > 0.0f && b > 0.0f);
}

// Sign comparison rather than a product, which underflows at small scales.
inline bool opposite_signs(float a, float b) {
  return (a < 0.0f && b > 0.0f) || (a > 0.0f && b < 0.0f);
}

inline float orient2d(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Whether c, within the tolerance of line ab, lies within segment ab's extent on ab's main
// axis (within length_tol).
inline bool within_extent_2d(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c,
                             float length_tol) {
  const int k = std::abs(b.x - a.x) >= std::abs(b.y - a.y) ? 0 : 1;
  return std::min(a[k], b[k]) - length_tol <= c[k] && c[k] <= std::max(a[k], b[k]) + length_tol;
}

// Closed segments ab and cd meet (within tolerance) in the projection plane. Where one segment's
// ends lie strictly on either side of the other's line, the crossing of the lines must lie within
// the other segment's extent; otherwise an end within the tolerance of the other's line must lie
// within the other's extent. An end near the other's line is not enough: nearly collinear
// segments a gap apart along the line have ends within the tolerance of each other's line (the
// lines cross far from both), which reported coplanar faces 0.2 x their size apart as meeting.
inline bool segments_meet_2d(const glm::vec2& a, const glm::vec2& b, const glm::vec2& c,
                             const glm::vec2& d, float area_tol, float length_tol) {
  const float r1 = orient2d(a, b, c);
  const float r2 = orient2d(a, b, d);
  const float r3 = orient2d(c, d, a);
  const float r4 = orient2d(c, d, b);
  const float o1 = snap_to_zero(r1, area_tol);
  const float o2 = snap_to_zero(r2, area_tol);
  const float o3 = snap_to_zero(r3, area_tol);
  const float o4 = snap_to_zero(r4, area_tol);
  if (o1 == 0.0f && o2 == 0.0f) {  // collinear: overlap of the 1D intervals on ab's main axis
    const int k = std::abs(b.x - a.x) >= std::abs(b.y - a.y) ? 0 : 1;
    return std::max(std::min(a[k], b[k]), std::min(c[k], d[k])) <=
           std::min(std::max(a[k], b[k]), std::max(c[k], d[k])) + length_tol;
  }
  // |r3|, |r4| > area_tol with opposite signs: no division by zero, the ratio in [0, 1].
  if (opposite_signs(o3, o4))
    return within_extent_2d(c, d, a + (b - a) * (r3 / (r3 - r4)), length_tol);
  if (opposite_signs(o1, o2))
    return within_extent_2d(a, b, c + (d - c) * (r1 / (r1 - r2)), length_tol);
  return (o1 == 0.0f && within_extent_2d(a, b, c, length_tol)) ||
         (o2 == 0.0f && within_extent_2d(a, b, d, length_tol)) ||
         (o3 == 0.0f && within_extent_2d(c, d, a, length_tol)) ||
         (o4 == 0.0f && within_extent_2d(c, d, b, length_tol));
}

// Point x inside or on the boundary of triangle t (either winding).
inline bool point_in_triangle_2d(const glm::vec2& x, const glm::vec2 t[3], float area_tol) {
  const float s0 = snap_to_zero(orient2d(t[0], t[1], x), area_tol);
  const float s1 = snap_to_zero(orient2d(t[1], t[2], x), area_tol);
  const float s2 = snap_to_zero(orient2d(t[2], t[0], x), area_tol);
  const bool has_negative = s0 < 0.0f || s1 < 0.0f || s2 < 0.0f;
  const bool has_positive = s0 > 0.0f || s1 > 0.0f || s2 > 0.0f;
  return !(has_negative && has_positive);
}

// Whether the closed bounding boxes of p and q share a point. min/max do not round, so this is
// exact on the float coordinates.
inline bool boxes_touch(const glm::vec3 p[3], const glm::vec3 q[3]) {
  for (int c = 0; c < 3; ++c) {
    const float p_min = std::min(std::min(p[0][c], p[1][c]), p[2][c]);
    const float p_max = std::max(std::max(p[0][c], p[1][c]), p[2][c]);
    const float q_min = std::min(std::min(q[0][c], q[1][c]), q[2][c]);
    const float q_max = std::max(std::max(q[0][c], q[1][c]), q[2][c]);
    if (p_max < q_min || q_max < p_min) return false;
  }
  return true;
}

// The two coordinates kept when projecting onto the coordinate plane where the normal n is
// largest (the projection with the least shrinkage).
inline void projection_axes(const glm::vec3& n, int& u, int& v) {
  const glm::vec3 m = glm::abs(n);
  u = 1;  // drop x
  v = 2;
  if (m.y >= m.x && m.y >= m.z) {  // drop y
    u = 0;
    v = 2;
  } else if (m.z >= m.x && m.z >= m.y) {  // drop z
    u = 0;
    v = 1;
  }
}

// Whether segment [s0, s1], lying on the plane of triangle t (normal n, within the tolerance),
// meets t, in the projection that drops n's largest coordinate, with the tolerances of a pair of
// size `size`. A segment shorter than the length tolerance is decided by its ends alone (the
// collinear branch of segments_meet_2d needs a direction).
inline bool segment_in_plane_meets_triangle(const glm::vec3& s0, const glm::vec3& s1,
                                            const glm::vec3 t[3], const glm::vec3& n, float size) {
  int u = 0;
  int v = 0;
  projection_axes(n, u, v);
  const auto project = [&](const glm::vec3& x) {  // relative to t[0]: small projected values
    return glm::vec2(x[u] - t[0][u], x[v] - t[0][v]);
  };
  const glm::vec2 t2[3] = {project(t[0]), project(t[1]), project(t[2])};
  const glm::vec2 a = project(s0);
  const glm::vec2 b = project(s1);
  const float area_tol = kTriTriTolerance * size * size;
  const float length_tol = kTriTriTolerance * size;
  if (point_in_triangle_2d(a, t2, area_tol) || point_in_triangle_2d(b, t2, area_tol)) return true;
  const glm::vec2 ab = b - a;
  if (!(glm::dot(ab, ab) > length_tol * length_tol)) return false;
  bool meet = false;
  for (int i = 0; i < 3; ++i)
    meet = meet || segments_meet_2d(a, b, t2[i], t2[(i + 1) % 3], area_tol, length_tol);
  return meet;
}

}  // namespace deformcd::collision::detail
