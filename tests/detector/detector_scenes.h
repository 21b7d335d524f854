#pragma once
// Meshes for the detector tests, as a caller of the public API would hold them: triangle lists
// with their own xyz arrays (std::vector<glm::vec3>), moved in place between passes.

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/detector.h"
#include "support/mesh_fixtures.h"

namespace deformcd::test {

/// A mesh and its positions, owned by the caller.
struct CallerMesh {
  CollisionMesh mesh;
  std::vector<glm::vec3> positions;
};

/// A sphere of radius r at `centre` (8 x 4^levels triangles, closed).
inline CallerMesh sphere_mesh(int levels, float r, glm::vec3 centre) {
  const SurfaceMesh s = sphere(levels);
  CallerMesh m;
  m.mesh.vertex_count = static_cast<std::uint32_t>(s.vertices.size());
  m.mesh.triangles = s.triangles;
  m.mesh.name = "sphere";
  for (const glm::dvec3& v : s.vertices)
    m.positions.push_back(centre + r * glm::vec3(v));
  return m;
}

/// An open square sheet of n x n quads (2 n^2 triangles) of side `size`, in the plane y = 0
/// centred at `centre`, its middle row of vertices lifted by `bulge` (a cloth draped over a
/// ridge), so that it crosses other meshes at general angles.
inline CallerMesh cloth_mesh(int n, float size, glm::vec3 centre, float bulge) {
  CallerMesh m;
  m.mesh.name = "cloth";
  const auto index = [n](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float u = static_cast<float>(i) / static_cast<float>(n) - 0.5f;
      const float v = static_cast<float>(j) / static_cast<float>(n) - 0.5f;
      const float lift = bulge * std::cos(3.0f * u) * std::cos(2.0f * v);
      m.positions.push_back(centre + glm::vec3(size * u, lift + 0.013f * u * v, size * v));
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.mesh.triangles.push_back({index(i, j), index(i + 1, j), index(i + 1, j + 1)});
      m.mesh.triangles.push_back({index(i, j), index(i + 1, j + 1), index(i, j + 1)});
    }
  }
  m.mesh.vertex_count = static_cast<std::uint32_t>(m.positions.size());
  return m;
}

/// Folds the cloth's far half (z > centre.z) over onto its near half, `gap` above it and
/// tilted, so that the two halves cross (self-contacts of an open surface).
inline void fold_cloth(CallerMesh& cloth, float centre_z, float tilt) {
  for (glm::vec3& p : cloth.positions) {
    if (p.z <= centre_z) continue;
    const float d = p.z - centre_z;
    p = glm::vec3(p.x, p.y + tilt * (d - 0.3f) + 0.02f * p.x, centre_z - d * 0.97f + 0.001f);
  }
}

}  // namespace deformcd::test
