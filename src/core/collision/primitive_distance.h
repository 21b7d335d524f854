#pragma once
// Distances between the primitives of a proximity pair (issue 12): a vertex and a triangle, or
// two edges (segments), and a bound on how fast their distance can shrink when every vertex
// moves along a straight path. The proximity search uses them to keep only the pairs that can
// come within reach in its period, the contact response to leave asleep the pairs that cannot
// be active yet. shaders/common/primitive_distance.glsl mirrors these functions line for line:
// change both together.

#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// The squared distance from p to segment (a, b) (to a when the segment is degenerate).
template <class T>
T point_segment_distance2(const glm::vec<3, T>& p, const glm::vec<3, T>& a,
                          const glm::vec<3, T>& b) {
  const glm::vec<3, T> ab = b - a;
  const T length2 = glm::dot(ab, ab);
  const T t = length2 > T(0) ? glm::clamp(glm::dot(p - a, ab) / length2, T(0), T(1)) : T(0);
  const glm::vec<3, T> d = p - (a + t * ab);
  return glm::dot(d, d);
}

/// The squared distance from p to triangle (a, b, c): the nearest of its three edges, or, when
/// p's projection on the plane falls inside the triangle, of that projection.
template <class T>
T point_triangle_distance2(const glm::vec<3, T>& p, const glm::vec<3, T>& a,
                           const glm::vec<3, T>& b, const glm::vec<3, T>& c) {
  T distance2 =
      glm::min(point_segment_distance2(p, a, b),
               glm::min(point_segment_distance2(p, b, c), point_segment_distance2(p, c, a)));
  const glm::vec<3, T> ab = b - a, ac = c - a, ap = p - a;
  const T d00 = glm::dot(ab, ab), d01 = glm::dot(ab, ac), d11 = glm::dot(ac, ac);
  const T d20 = glm::dot(ap, ab), d21 = glm::dot(ap, ac);
  const T denominator = d00 * d11 - d01 * d01;
  if (denominator > T(0)) {
    const T v = (d11 * d20 - d01 * d21) / denominator;
    const T w = (d00 * d21 - d01 * d20) / denominator;
    if (v >= T(0) && w >= T(0) && v + w <= T(1)) {
      const glm::vec<3, T> d = ap - (v * ab + w * ac);
      distance2 = glm::min(distance2, glm::dot(d, d));
    }
  }
  return distance2;
}

/// Parameters (s, t) of the closest points a0 + s (a1 - a0) and b0 + t (b1 - b0) of two
/// segments, each in [0, 1]; false when either segment is degenerate.
template <class T>
bool segment_closest_parameters(const glm::vec<3, T>& a0, const glm::vec<3, T>& a1,
                                const glm::vec<3, T>& b0, const glm::vec<3, T>& b1, T& s, T& t) {
  const glm::vec<3, T> da = a1 - a0, db = b1 - b0, r = a0 - b0;
  const T aa = glm::dot(da, da), bb = glm::dot(db, db), ab = glm::dot(da, db);
  const T ar = glm::dot(da, r), br = glm::dot(db, r);
  if (!(aa > T(0)) || !(bb > T(0))) return false;
  const T denominator = aa * bb - ab * ab;
  // Parallel segments: any s works; take the one of a0 and let t and then s clamp.
  s = denominator > T(1e-12) * aa * bb ? glm::clamp((ab * br - bb * ar) / denominator, T(0), T(1))
                                       : T(0);
  t = (ab * s + br) / bb;
  if (t < T(0)) {
    t = T(0);
    s = glm::clamp(-ar / aa, T(0), T(1));
  } else if (t > T(1)) {
    t = T(1);
    s = glm::clamp((ab - ar) / aa, T(0), T(1));
  }
  return true;
}

/// The squared distance between a pair's primitives, in double precision from their float
/// coordinates (in float, the barycentric weights of a sliver's projection, or of a point
/// just inside a thin triangle, can be off by more than the point's distance): kind
/// kContactVertexFace, vertex x[0] and triangle (x[1], x[2], x[3]); kContactEdgeEdge, segments
/// (x[0], x[1]) and (x[2], x[3]) (a degenerate segment is a point).
inline double primitive_distance2(std::uint32_t kind, const glm::vec3 x[4]) {
  const glm::dvec3 y[4] = {glm::dvec3(x[0]), glm::dvec3(x[1]), glm::dvec3(x[2]), glm::dvec3(x[3])};
  if (kind != gpu::kContactEdgeEdge) return point_triangle_distance2(y[0], y[1], y[2], y[3]);
  double s = 0.0, t = 0.0;
  if (!segment_closest_parameters(y[0], y[1], y[2], y[3], s, t)) {
    // A degenerate segment is a point (point_segment_distance2 takes a degenerate one too).
    return y[0] == y[1] ? point_segment_distance2(y[0], y[2], y[3])
                        : point_segment_distance2(y[2], y[0], y[1]);
  }
  const glm::dvec3 d = (y[0] + s * (y[1] - y[0])) - (y[2] + t * (y[3] - y[2]));
  return glm::dot(d, d);
}

/// The distance between a pair's primitives (primitive_distance2), rounded to float.
inline float primitive_distance(std::uint32_t kind, const glm::vec3 x[4]) {
  return static_cast<float>(std::sqrt(primitive_distance2(kind, x)));
}

/// Whether a pair's primitives, at x, can come within `reach` of each other while their
/// distance shrinks by at most `closing` (closing_speed x the period): distance - closing <=
/// reach, compared squared in double (no square root to round differently on another backend).
/// When the pair is within, its exact distance is stored in *distance (primitive_distance's
/// value) if `distance` is not null.
inline bool primitives_within(std::uint32_t kind, const glm::vec3 x[4], float closing, float reach,
                              float* distance = nullptr) {
  // First a float lower bound of the distance: the triangle's plane (a vertex-face pair) or
  // the segments' bounding spheres (an edge pair). It rejects most of the pairs a box test
  // lets through; its margin (1e-5 of the lengths involved, 1e-3 of the limit) covers its
  // rounding, so that only pairs the exact distance would reject are rejected here.
  const float limit_f = reach + closing;
  if (kind == gpu::kContactEdgeEdge) {
    const glm::vec3 between = 0.5f * (x[0] + x[1]) - 0.5f * (x[2] + x[3]);
    const float radii = 0.5f * (glm::length(x[1] - x[0]) + glm::length(x[3] - x[2]));
    const float centres = glm::length(between);
    if (centres - radii > 1.001f * limit_f + 1e-5f * (centres + radii)) return false;
  } else {
    const glm::vec3 normal = glm::cross(x[2] - x[1], x[3] - x[1]);
    const float area2 = glm::length(normal);
    const glm::vec3 offset = x[0] - x[1];
    const float height = glm::abs(glm::dot(offset, normal));
    const float span = glm::length(offset);
    if (area2 > 0.0f && height > area2 * (1.001f * limit_f + 1e-5f * span)) return false;
  }
  const double limit = static_cast<double>(reach) + static_cast<double>(closing);
  const double distance2 = primitive_distance2(kind, x);
  if (distance2 > limit * limit) return false;
  if (distance != nullptr) *distance = static_cast<float>(std::sqrt(distance2));
  return true;
}

/// The largest of a pair's per-vertex values (>= 0) on its first side (the vertex, or the first
/// edge) plus the largest on its second (the face's corners, or the second edge): what moving
/// each vertex by its value can take off the primitives' distance, at most.
inline float largest_per_side(std::uint32_t kind, const float value[4]) {
  const std::uint32_t first_b = kind == gpu::kContactEdgeEdge ? 2u : 1u;
  float side_a = 0.0f, side_b = 0.0f;
  for (std::uint32_t k = 0; k < 4u; ++k) {
    if (k < first_b) {
      side_a = glm::max(side_a, value[k]);
    } else {
      side_b = glm::max(side_b, value[k]);
    }
  }
  return side_a + side_b;
}

/// How fast a pair's distance can shrink when each vertex moves at m[k] (any unit): the
/// distance is unchanged by a common motion, so with `mean` the mean of the four, it shrinks by
/// at most the fastest of one side's |m - mean| plus the fastest of the other's (each point of
/// a primitive is a convex combination of its vertices). Sides as in primitive_distance.
inline float closing_speed(std::uint32_t kind, const glm::vec3 m[4]) {
  const glm::vec3 mean = ((m[0] + m[1]) + (m[2] + m[3])) * 0.25f;
  float speed[4];
  for (std::uint32_t k = 0; k < 4u; ++k)
    speed[k] = glm::length(m[k] - mean);
  return largest_per_side(kind, speed);
}

}  // namespace deformcd::collision
