#pragma once
// A bound on the float narrow phase's false contacts: whatever its tolerances snap, they move
// no vertex farther than the plane tolerance, nor a point farther than the 2D orientation
// tolerance from an edge's line, so a pair it reports as touching while CGAL says apart must lie
// within that distance of touching. zone_measure (support/tri_tri_zone.h) does not check this:
// for nearly parallel, nearly coplanar pairs it returns the planes' distance, however far apart
// the triangles are within their planes.

#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <array>
#include <cmath>

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

}  // namespace deformcd::test
