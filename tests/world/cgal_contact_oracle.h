#pragma once
// The exact answer for two bodies' surfaces: every pair of faces (a of one body, b of the
// other) that CGAL's do_intersect with exact predicates says intersects, on the same float
// positions a world holds. Used by collision_cgal_models_test.cpp.

#include <CGAL/intersections.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "deformcd/body.h"
#include "deformcd/world.h"
#include "support/tri_tri_zone.h"

namespace deformcd::test {

/// A closed axis-aligned box in float: min/max of floats do not round, so box tests are exact.
struct FloatBox {
  glm::vec3 lo{3.4e38f};
  glm::vec3 hi{-3.4e38f};

  void grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  [[nodiscard]] bool touches(const FloatBox& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z &&
           o.lo.z <= hi.z;
  }
};

/// One body's surface triangles (in face order) with their bounding boxes.
struct Surface {
  std::vector<Tri> triangles;
  std::vector<FloatBox> boxes;
  FloatBox bounds;
};

/// `faces` with indices into `positions` after subtracting `node_offset`.
inline Surface make_surface(const std::vector<glm::vec3>& positions, const gpu::Face* faces,
                            std::size_t face_count, std::uint32_t node_offset) {
  Surface s;
  s.triangles.reserve(face_count);
  s.boxes.reserve(face_count);
  for (std::size_t f = 0; f < face_count; ++f) {
    const gpu::Face& face = faces[f];
    const Tri t{positions.at(face.a - node_offset), positions.at(face.b - node_offset),
                positions.at(face.c - node_offset)};
    FloatBox box;
    for (const glm::vec3& p : t)
      box.grow(p);
    s.triangles.push_back(t);
    s.boxes.push_back(box);
    s.bounds.grow(box.lo);
    s.bounds.grow(box.hi);
  }
  return s;
}

/// Body `body` of a world as it is now. World::faces() holds global node indices.
inline Surface world_surface(const World& world, std::size_t body) {
  const gpu::ObjectInfo& o = world.object(body);
  return make_surface(world.positions(body), world.faces().data() + o.face_offset, o.face_count,
                      o.node_offset);
}

/// A body before it is put in a world (its faces hold local node indices).
inline Surface body_surface(const Body& body) {
  const std::vector<glm::vec3> positions(body.positions.begin(), body.positions.end());
  return make_surface(positions, body.faces.data(), body.faces.size(), 0u);
}

/// The face pairs (face of a, face of b) that intersect exactly, sorted.
struct ExactPairs {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::size_t tested = 0;      ///< pairs handed to CGAL
  std::size_t degenerate = 0;  ///< faces CGAL calls degenerate (outside its precondition)
};

inline ExactPairs exact_intersections(const Surface& a, const Surface& b) {
  ExactPairs out;
  std::vector<CgalKernel::Triangle_3> cgal_b;
  cgal_b.reserve(b.triangles.size());
  for (const Tri& t : b.triangles)
    cgal_b.push_back(to_cgal(t));
  // Faces whose closed float box misses the other body's box, or the other face's box, cannot
  // meet it: the prefilter is exact and loses no true intersection (touching boxes are kept).
  std::vector<std::uint32_t> near_a;
  std::vector<std::uint32_t> near_b;
  for (std::uint32_t i = 0; i < a.boxes.size(); ++i)
    if (a.boxes[i].touches(b.bounds)) near_a.push_back(i);
  for (std::uint32_t j = 0; j < b.boxes.size(); ++j)
    if (b.boxes[j].touches(a.bounds)) near_b.push_back(j);
  std::vector<char> degenerate_b(b.triangles.size(), 0);
  for (std::uint32_t j : near_b) {
    degenerate_b[j] = cgal_b[j].is_degenerate() ? 1 : 0;
    out.degenerate += degenerate_b[j] != 0 ? 1u : 0u;
  }
  for (std::uint32_t i : near_a) {
    const CgalKernel::Triangle_3 ta = to_cgal(a.triangles[i]);
    if (ta.is_degenerate()) {
      ++out.degenerate;
      continue;
    }
    for (std::uint32_t j : near_b) {
      if (!a.boxes[i].touches(b.boxes[j]) || degenerate_b[j] != 0) continue;
      ++out.tested;
      if (CGAL::do_intersect(ta, cgal_b[j])) out.pairs.emplace_back(i, j);
    }
  }
  return out;
}

}  // namespace deformcd::test
