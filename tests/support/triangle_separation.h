#pragma once
// What a disagreement between the float narrow phase and CGAL's exact answer may be, measured
// on the pair's own geometry rather than on the algorithm's intermediate values:
//  - a contact CGAL does not see: whatever the tolerances snap, they move no vertex farther than
//    the plane tolerance, nor a point farther than the 2D orientation tolerance from an edge's
//    line, so the pair must lie within that distance of touching (separation_measure);
//  - an intersection the float test misses: the pair must lie within the tolerance of apart
//    (apart_measure), or in zone_measure's uncertain zone.
// zone_measure (support/tri_tri_zone.h) alone does neither for nearly parallel, nearly coplanar
// pairs: it returns the planes' distance or the 2D configuration's margin, however far apart the
// triangles lie within their planes (false contacts 0.5 x the size apart passed), and however
// little a vertex must move to part them (nearly parallel crossings, a vertex snapped).

#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include <glm/geometric.hpp>

#include "support/tri_tri_zone.h"

namespace deformcd::test {

/// The distance between triangles p and q (0 when they meet), in double.
inline double triangle_distance(const Tri& p, const Tri& q) {
  if (CGAL::do_intersect(to_cgal(p), to_cgal(q))) return 0.0;
  // Apart: the closest points are a vertex and the other triangle, or two edges.
  double d2 = 1e300;
  for (int i = 0; i < 3; ++i) {
    d2 = std::min(d2, CGAL::squared_distance(to_cgal(p[i]), to_cgal(q)));
    d2 = std::min(d2, CGAL::squared_distance(to_cgal(q[i]), to_cgal(p)));
    const CgalKernel::Segment_3 ep(to_cgal(p[i]), to_cgal(p[(i + 1) % 3]));
    for (int j = 0; j < 3; ++j) {
      const CgalKernel::Segment_3 eq(to_cgal(q[j]), to_cgal(q[(j + 1) % 3]));
      d2 = std::min(d2, CGAL::squared_distance(ep, eq));
    }
  }
  return std::sqrt(d2);
}

/// triangle_distance over the largest distance the algorithm's tolerances can bridge, as a
/// multiple of kTriTriTolerance: the pair's size S times the largest of each triangle's plane
/// tolerance unit (1 + (roundoff / tolerance) L^2 / |n|) and sqrt(3) S / (its shortest edge)
/// (an orientation snapped below kTriTriTolerance S^2 puts a point that far from a projected
/// edge, which the dominant projection shortens by at most sqrt(3)). Below kZone, a contact
/// CGAL does not see is one the tolerances may make; p and q must not be near-degenerate.
inline double separation_measure(const Tri& p, const Tri& q) {
  double size2 = 0.0;
  double unit = 1.0;
  double shortest2 = 1e300;
  for (const Tri* t : {&p, &q}) {
    const auto d = zone_detail::to_double(*t);
    const double l2 = zone_detail::longest_edge2(d);
    const glm::dvec3 n = glm::cross(d[1] - d[0], d[2] - d[0]);
    size2 = std::max(size2, l2);
    unit = std::max(unit, zone_detail::plane_scale(n, l2) / glm::length(n));
    for (int i = 0; i < 3; ++i) {
      const glm::dvec3 e = d[(i + 1) % 3] - d[i];
      shortest2 = std::min(shortest2, glm::dot(e, e));
    }
  }
  const double size = std::sqrt(size2);
  unit = std::max(unit, std::sqrt(3.0) * size / std::sqrt(shortest2));
  return triangle_distance(p, q) / (size * unit);
}

/// How far one triangle must move along the other's normal to lie strictly on one side of the
/// other's plane, the smaller over the two, in zone_measure's units for a vertex near a plane
/// (distance / ((|n| + (roundoff / tolerance) L^2) S), the algorithm's plane tolerance over
/// kTriTriTolerance). Pushed by a little more than that, the triangles are exactly apart: below
/// kZone, an intersection CGAL sees is one the float test may miss, e.g. nearly parallel faces
/// crossing, whose line of intersection a vertex within the tolerance of the plane moves far.
inline double apart_measure(const Tri& p, const Tri& q) {
  const auto pd = zone_detail::to_double(p);
  const auto qd = zone_detail::to_double(q);
  const double lp2 = zone_detail::longest_edge2(pd);
  const double lq2 = zone_detail::longest_edge2(qd);
  const double size = std::sqrt(std::max(lp2, lq2));
  double best = 1e300;
  for (const auto& [t, o, o2] : {std::tuple{&pd, &qd, lq2}, std::tuple{&qd, &pd, lp2}}) {
    const glm::dvec3 n = glm::cross((*o)[1] - (*o)[0], (*o)[2] - (*o)[0]);
    const double unit = zone_detail::plane_scale(n, o2) * size;
    double above = 0.0;  // the push that puts t wholly below the plane, and above it
    double below = 0.0;
    for (const glm::dvec3& x : *t) {
      const double d = glm::dot(n, x - (*o)[0]) / unit;
      above = std::max(above, d);
      below = std::max(below, -d);
    }
    best = std::min({best, above, below});
  }
  return best;
}

/// The measure a disagreement must keep below kZone, `cgal` being CGAL's answer: for a contact
/// CGAL does not see, separation_measure; for an intersection the float test misses, the smaller
/// of zone_measure and apart_measure. p and q must not be near-degenerate.
inline double disagreement_measure(const Tri& p, const Tri& q, bool cgal) {
  if (!cgal) return separation_measure(p, q);
  return std::min(zone_measure(p, q), apart_measure(p, q));
}

}  // namespace deformcd::test
