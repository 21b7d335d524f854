#pragma once
// Small meshes built in code for tests.

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "deformcd/mesh.h"

namespace deformcd::test {

/// One positively oriented tetrahedron with unit legs at the origin.
inline TetMesh unit_tetrahedron() {
  TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.tetrahedra = {{0, 1, 2, 3}};
  return m;
}

/// The unit cube [0,1]^3 split into 5 positively oriented tetrahedra (8 nodes, 12 surface
/// triangles, volume 1).
inline TetMesh unit_cube() {
  TetMesh m;
  m.nodes = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
             {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  // Corner tetrahedra at nodes 0, 2, 5, 7 and the central one (1, 3, 4, 6).
  m.tetrahedra = {{0, 1, 3, 4}, {2, 3, 1, 6}, {5, 4, 6, 1}, {7, 6, 4, 3}, {1, 3, 4, 6}};
  return m;
}

/// A closed, outward-oriented cube surface: 8 vertices (cube_corners: 0-3 at z = 0, 4-7 at
/// z = 1; 0, 3, 4, 7 at x = 0) and 12 triangles (6 and 7 on its x = 1 side, 10 and 11 on its
/// x = 0 side).
inline const std::vector<Triangle>& cube_triangles() {
  static const std::vector<Triangle> triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                                  {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                                  {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  return triangles;
}

/// The corners of the cube [lo, lo + size]^3, numbered as cube_triangles() expects.
inline std::vector<glm::vec3> cube_corners(const glm::vec3& lo, float size) {
  std::vector<glm::vec3> v;
  for (int z = 0; z < 2; ++z)
    for (const glm::vec2 corner :
         {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
      v.push_back(lo + size * glm::vec3(corner.x, corner.y, static_cast<float>(z)));
  return v;
}

/// A closed, outward-oriented octahedron surface (6 vertices, 8 triangles).
inline SurfaceMesh octahedron() {
  SurfaceMesh s;
  s.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

/// The octahedron subdivided `levels` times and projected onto the unit sphere: a closed,
/// outward-oriented surface with 8 x 4^levels triangles.
inline SurfaceMesh sphere(int levels) {
  SurfaceMesh s = octahedron();
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.emplace(key, static_cast<std::uint32_t>(s.vertices.size()));
      if (inserted) s.vertices.push_back(glm::normalize(s.vertices[a] + s.vertices[b]));
      return it->second;
    };
    std::vector<Triangle> finer;
    for (const Triangle& t : s.triangles) {
      const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]),
                          ca = midpoint(t[2], t[0]);
      finer.push_back({t[0], ab, ca});
      finer.push_back({ab, t[1], bc});
      finer.push_back({ca, bc, t[2]});
      finer.push_back({ab, bc, ca});
    }
    s.triangles = std::move(finer);
  }
  return s;
}

}  // namespace deformcd::test
