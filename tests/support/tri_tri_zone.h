#pragma once
// Shared by the exact-oracle tests of the narrow phase (CGAL's do_intersect on Triangle_3 with
// exact predicates against tri_tri_intersect): the conversion to CGAL and the uncertain-zone
// measure, which says whether a disagreement is one the float algorithm is allowed to make.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/collision/tri_tri_intersection.h"

namespace deformcd::test {

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tri = std::array<glm::vec3, 3>;

// Twice the algorithm's tolerance: the float algorithm evaluates the same quantities as the
// double zone measure below, with a few ulps of rounding, and snaps at kTriTriTolerance.
inline constexpr double kZone = 2.0 * collision::kTriTriTolerance;

inline CgalKernel::Point_3 to_cgal(const glm::vec3& v) {  // float -> double is exact
  return {static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)};
}

/// Moves p and q into a plane that float represents exactly: y = x when `diagonal`, else z = 0,
/// so that they are coplanar exactly (random coplanar pairs for the oracles).
inline void flatten_to_exact_plane(Tri& p, Tri& q, bool diagonal) {
  for (Tri* t : {&p, &q}) {
    for (glm::vec3& x : *t) {
      if (diagonal)
        x.y = x.x;
      else
        x.z = 0.0f;
    }
  }
}

/// Triangles p and q in hexadecimal floats (exact, to paste into a failing case).
inline std::string describe_pair(const Tri& p, const Tri& q) {
  std::ostringstream text;
  text << std::hexfloat;
  for (const Tri* t : {&p, &q})
    for (const glm::vec3& v : *t)
      text << " {" << v.x << ", " << v.y << ", " << v.z << "}";
  return text.str();
}

inline CgalKernel::Triangle_3 to_cgal(const Tri& t) {
  return {to_cgal(t[0]), to_cgal(t[1]), to_cgal(t[2])};
}

namespace zone_detail {

inline std::array<glm::dvec3, 3> to_double(const Tri& t) {
  return {glm::dvec3(t[0]), glm::dvec3(t[1]), glm::dvec3(t[2])};
}

inline double longest_edge2(const std::array<glm::dvec3, 3>& t) {
  return std::max({glm::dot(t[1] - t[0], t[1] - t[0]), glm::dot(t[2] - t[1], t[2] - t[1]),
                   glm::dot(t[0] - t[2], t[0] - t[2])});
}

inline double orient2d(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// |n| plus the rounding term of the plane tolerance, as a multiple of kTriTriTolerance.
inline double plane_scale(const glm::dvec3& n, double longest2) {
  return glm::length(n) +
         double(collision::kTriTriRoundoff) / double(collision::kTriTriTolerance) * longest2;
}

}  // namespace zone_detail

// How far (relative, dimensionless) the pair is from a configuration where the answer changes,
// in the terms of the algorithm's tolerances; below kZone the pair is in the uncertain zone.
//  - a near-degenerate triangle: |n| / longest_edge^2;
//  - a vertex near the other plane: |dot(n, x - a0)| / ((|n| + (roundoff / tolerance) x
//    longest_edge^2) x pair size), the algorithm's plane tolerance over kTriTriTolerance;
//  - coplanar pairs (all three vertices of one near the other's plane): the smallest 2D
//    orientation of a vertex against the other's edges / size^2 in the dominant projection,
//    unless those three vertices are all on one side of the plane (parallel but apart): then
//    their largest distance to it, as above;
//  - otherwise the gap (or overlap) of the two intervals on the planes' line, times the sine of
//    the planes' angle (what the gap means as a distance between the triangles) / size.
inline double zone_measure(const Tri& pf, const Tri& qf) {
  using glm::dvec3;
  using zone_detail::longest_edge2;
  using zone_detail::orient2d;
  using zone_detail::plane_scale;
  const auto p = zone_detail::to_double(pf);
  const auto q = zone_detail::to_double(qf);
  const double lp2 = longest_edge2(p);
  const double lq2 = longest_edge2(q);
  const double size = std::sqrt(std::max(lp2, lq2));
  const dvec3 np = glm::cross(p[1] - p[0], p[2] - p[0]);
  const dvec3 nq = glm::cross(q[1] - q[0], q[2] - q[0]);
  const double degenerate = std::min(glm::length(np) / lp2, glm::length(nq) / lq2);
  if (degenerate < 2.0 * collision::kTriTriDegenerateTolerance) return 0.0;
  double dq[3];
  double dp[3];
  for (int i = 0; i < 3; ++i) {
    dq[i] = glm::dot(np, q[i] - p[0]) / (plane_scale(np, lp2) * size);
    dp[i] = glm::dot(nq, p[i] - q[0]) / (plane_scale(nq, lq2) * size);
  }
  auto near_plane = [](const double d[3]) {
    return std::abs(d[0]) < kZone && std::abs(d[1]) < kZone && std::abs(d[2]) < kZone;
  };
  auto one_side = [](const double d[3]) {
    return (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0);
  };
  if (near_plane(dq) || near_plane(dp)) {
    // Planes closer than the zone with one triangle wholly on one side of the other's plane:
    // exactly apart, but the algorithm snaps that triangle onto the plane and tests the overlap
    // in 2D; flattening it (moving each vertex by less than the zone) makes them touch.
    for (const double* d : {dq, dp}) {
      if (near_plane(d) && one_side(d))
        return std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
    }
    const dvec3 m = glm::abs(np);
    const int drop = (m.x >= m.y && m.x >= m.z) ? 0 : (m.y >= m.z ? 1 : 2);
    const int u = drop == 0 ? 1 : 0;
    const int v = drop == 2 ? 1 : 2;
    double smallest = 1e300;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const int k = (j + 1) % 3;
        smallest = std::min(smallest, std::abs(orient2d({p[j][u], p[j][v]}, {p[k][u], p[k][v]},
                                                        {q[i][u], q[i][v]})));
        smallest = std::min(smallest, std::abs(orient2d({q[j][u], q[j][v]}, {q[k][u], q[k][v]},
                                                        {p[i][u], p[i][v]})));
      }
    }
    return smallest / (size * size);
  }
  double measure = 1e300;
  for (int i = 0; i < 3; ++i)
    measure = std::min({measure, std::abs(dq[i]), std::abs(dp[i])});
  // Interval gap on the line (only meaningful when both cross the other's plane).
  const dvec3 up = np / glm::length(np);
  const dvec3 uq = nq / glm::length(nq);
  const dvec3 dir = glm::cross(up, uq);
  const double sine = glm::length(dir);
  if (sine == 0.0) return measure;
  auto interval = [&](const std::array<dvec3, 3>& t, const dvec3& n, const dvec3& o,
                      double out[2]) {
    out[0] = 1e300;
    out[1] = -1e300;
    double d[3];
    for (int i = 0; i < 3; ++i)
      d[i] = glm::dot(n, t[i] - o);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      if (d[i] == 0.0 || (d[i] < 0.0) != (d[j] < 0.0)) {
        const dvec3 x = d[i] == 0.0 ? t[i] : t[i] + (t[j] - t[i]) * (d[i] / (d[i] - d[j]));
        const double s = glm::dot(dir, x - p[0]) / sine;
        out[0] = std::min(out[0], s);
        out[1] = std::max(out[1], s);
      }
    }
    return out[0] <= out[1];
  };
  double ip[2];
  double iq[2];
  if (interval(p, uq, q[0], ip) && interval(q, up, p[0], iq)) {
    const double gap = std::max(ip[0], iq[0]) - std::min(ip[1], iq[1]);
    measure = std::min(measure, std::abs(gap) * sine / size);
  }
  return measure;
}

}  // namespace deformcd::test
