#pragma once
// Exact answer and uncertain zone for faces sharing one node (tri_tri_intersect_sharing_vertex),
// for the exact-oracle tests of self-collision. Two triangles p, q with p[0] == q[0] = v meet
// beyond v exactly when the edge opposite v of one meets the other triangle (the rule of
// core/collision/face_pair_intersection.h, and of CGAL's Polygon_mesh_processing
// self-intersection test): each of those two segment-triangle tests is decided here with CGAL's
// exact predicates, and given a measure of how far it is from changing its answer.

#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "support/tri_tri_zone.h"

namespace deformcd::test {

/// Whether the closed segment [s0, s1] meets triangle t, exactly (t must not be degenerate).
inline bool exact_segment_meets_triangle(const glm::vec3& s0, const glm::vec3& s1, const Tri& t) {
  return CGAL::do_intersect(CgalKernel::Segment_3(to_cgal(s0), to_cgal(s1)), to_cgal(t));
}

/// Whether the float narrow phase takes t as degenerate, with a margin of 2 for rounding.
inline bool near_degenerate(const Tri& tf) {
  const auto t = zone_detail::to_double(tf);
  const double n_len = glm::length(glm::cross(t[1] - t[0], t[2] - t[0]));
  return n_len / zone_detail::longest_edge2(t) < 2.0 * collision::kTriTriDegenerateTolerance;
}

namespace zone_detail {

inline glm::dvec2 project(const glm::dvec3& x, int u, int v) {
  return {x[u], x[v]};
}

// The smallest |orient2d| of x against t's edges, in the projection onto axes u, v.
inline double smallest_orientation(const glm::dvec3& x, const std::array<glm::dvec3, 3>& t, int u,
                                   int v) {
  double smallest = 1e300;
  for (int i = 0; i < 3; ++i) {
    smallest = std::min(
        smallest,
        std::abs(orient2d(project(t[i], u, v), project(t[(i + 1) % 3], u, v), project(x, u, v))));
  }
  return smallest;
}

}  // namespace zone_detail

/// How far (relative, dimensionless) the segment [s0, s1] and triangle t are from a
/// configuration where "they meet" changes, in the terms of segment_triangle_meet's tolerances;
/// below kZone the pair is in the uncertain zone. The answer changes only where an end of the
/// segment touches t or the segment touches an edge of t, so the measure is the least of
///  - those distances (ends to t, segment to t's edges), over the algorithm's plane tolerance
///    (kTriTriTolerance plus the rounding term, times the size S = max(t's longest edge, the
///    segment's length)). For a segment crossing t at a small angle a, the float crossing point
///    moves by (plane rounding) / sin(a) along t, while the segment passes within
///    (distance of the crossing to an edge) x sin(a) of that edge: the segment-edge distance
///    measures both;
///  - the 2D orientations the algorithm snaps (over S^2, in t's dominant projection): of the
///    crossing point, or of an end near t's plane, against t's edges, and for a segment near
///    the plane, of t's vertices against it;
///  - 0 for a near-degenerate t (which the algorithm says meets nothing).
inline double segment_zone_measure(const glm::vec3& s0f, const glm::vec3& s1f, const Tri& tf) {
  using glm::dvec3;
  using zone_detail::orient2d;
  using zone_detail::project;
  const auto t = zone_detail::to_double(tf);
  const dvec3 s0(s0f);
  const dvec3 s1(s1f);
  const double l2 = zone_detail::longest_edge2(t);
  const dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
  const double n_len = glm::length(n);
  if (near_degenerate(tf)) return 0.0;
  const double size = std::sqrt(std::max(l2, glm::dot(s1 - s0, s1 - s0)));
  // The algorithm's plane tolerance, relative to S and as a multiple of kTriTriTolerance.
  const double plane_unit = zone_detail::plane_scale(n, l2) / n_len;

  const CgalKernel::Triangle_3 ct = to_cgal(tf);
  const CgalKernel::Segment_3 cs(to_cgal(s0f), to_cgal(s1f));
  double distance2 =
      std::min(CGAL::squared_distance(to_cgal(s0f), ct), CGAL::squared_distance(to_cgal(s1f), ct));
  for (int i = 0; i < 3; ++i) {
    const CgalKernel::Segment_3 edge(to_cgal(tf[i]), to_cgal(tf[(i + 1) % 3]));
    distance2 = std::min(distance2, CGAL::squared_distance(cs, edge));
  }
  double measure = std::sqrt(distance2) / (size * plane_unit);

  const dvec3 m = glm::abs(n);
  const int drop = (m.x >= m.y && m.x >= m.z) ? 0 : (m.y >= m.z ? 1 : 2);
  const int u = drop == 0 ? 1 : 0;
  const int v = drop == 2 ? 1 : 2;
  const double d0 = glm::dot(n, s0 - t[0]) / n_len;
  const double d1 = glm::dot(n, s1 - t[0]) / n_len;
  const bool near0 = std::abs(d0) / (size * plane_unit) < kZone;
  const bool near1 = std::abs(d1) / (size * plane_unit) < kZone;
  double orientation = 1e300;
  if (near0) orientation = std::min(orientation, zone_detail::smallest_orientation(s0, t, u, v));
  if (near1) orientation = std::min(orientation, zone_detail::smallest_orientation(s1, t, u, v));
  if (near0 && near1) {  // the in-plane test: t's vertices against the segment's line too
    for (const dvec3& x : t) {
      orientation = std::min(
          orientation, std::abs(orient2d(project(s0, u, v), project(s1, u, v), project(x, u, v))));
    }
  }
  if ((d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0)) {
    const dvec3 crossing = s0 + (s1 - s0) * (d0 / (d0 - d1));
    orientation = std::min(orientation, zone_detail::smallest_orientation(crossing, t, u, v));
  }
  return std::min(measure, orientation / (size * size));
}

/// The exact answer for triangles p and q sharing their first vertex, and the zone measure of
/// that answer (see segment_zone_measure), from its two segment-triangle tests.
struct SharedVertexOracle {
  bool p_edge_meets_q = false;  ///< p's edge opposite v meets q
  bool q_edge_meets_p = false;  ///< q's edge opposite v meets p
  double p_edge_measure = 0.0;
  double q_edge_measure = 0.0;

  [[nodiscard]] bool intersect() const { return p_edge_meets_q || q_edge_meets_p; }
  /// Below kZone, a float answer other than intersect() is allowed. When the pair meets,
  /// every test that says so must have flipped for a float "no"; when it does not, one
  /// flipped test makes a float "yes".
  [[nodiscard]] double measure() const {
    if (p_edge_meets_q && q_edge_meets_p) return std::max(p_edge_measure, q_edge_measure);
    if (p_edge_meets_q) return p_edge_measure;
    if (q_edge_meets_p) return q_edge_measure;
    return std::min(p_edge_measure, q_edge_measure);
  }
};

/// p[0] and q[0] must be the same point; neither triangle exactly degenerate. A near-degenerate
/// triangle (which the float test says meets nothing) puts the pair in the zone (measure 0).
inline SharedVertexOracle shared_vertex_oracle(const Tri& p, const Tri& q) {
  SharedVertexOracle o;
  o.p_edge_meets_q = exact_segment_meets_triangle(p[1], p[2], q);
  o.q_edge_meets_p = exact_segment_meets_triangle(q[1], q[2], p);
  o.p_edge_measure = segment_zone_measure(p[1], p[2], q);
  o.q_edge_measure = segment_zone_measure(q[1], q[2], p);
  if (near_degenerate(p) || near_degenerate(q)) {
    o.p_edge_measure = 0.0;
    o.q_edge_measure = 0.0;
  }
  return o;
}

}  // namespace deformcd::test
