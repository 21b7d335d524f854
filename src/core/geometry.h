#pragma once
// Small pure geometric functions shared by the core (double precision).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace deformcd::geom {

/// Six times the signed volume of tetrahedron (a, b, c, d): positive when d lies on the side
/// of plane (a, b, c) that its counter-clockwise normal points to.
inline double signed_volume6(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                             const glm::dvec3& d) {
  return glm::dot(b - a, glm::cross(c - a, d - a));
}

/// Twice the area of triangle (a, b, c).
inline double double_area(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return glm::length(glm::cross(b - a, c - a));
}

inline double longest_edge2(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return std::max({glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
}

inline bool is_finite(const glm::dvec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

}  // namespace deformcd::geom
