#pragma once
// The exact narrow phase of the peers without a triangle-triangle test of their own (CGAL's
// broad phase, Bullet's btDbvt): CGAL's do_intersect on two Triangle_3 of the Epick kernel
// (exact predicates, filtered: interval arithmetic first, exact only when that is undecided),
// made from the frame's float positions (converted to double exactly). Touching counts as
// intersecting, as in deformcd's test.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/mesh.h"

namespace deformcd::bench {

/// Whether triangle `a` (its vertices in `pa`) and triangle `b` (in `pb`) intersect, exactly.
inline bool exact_triangles_intersect(const std::vector<glm::vec3>& pa, const Triangle& a,
                                      const std::vector<glm::vec3>& pb, const Triangle& b) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  const auto triangle = [](const std::vector<glm::vec3>& p, const Triangle& t) {
    const auto point = [&](std::uint32_t v) { return Kernel::Point_3(p[v].x, p[v].y, p[v].z); };
    return Kernel::Triangle_3(point(t[0]), point(t[1]), point(t[2]));
  };
  return CGAL::do_intersect(triangle(pa, a), triangle(pb, b));
}

}  // namespace deformcd::bench
