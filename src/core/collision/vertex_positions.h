#pragma once
// Where a collision pass reads the vertex positions of each mesh: in place, from the arrays the
// caller (or the simulation) owns, one array per mesh with its own stride. GLSL reads them the
// same way from one float buffer, with a word offset and stride per mesh (MeshInfo::position_*;
// shaders/collision/surface.glsl, vertex_position): change both together.

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// One mesh's positions: vertex i's x, y, z are data[i * stride], [+ 1], [+ 2].
struct MeshVertices {
  const float* data = nullptr;
  std::uint32_t stride = 3;  ///< floats from one vertex to the next
};

/// Every mesh's positions, indexed by mesh (Face::body).
using VertexPositions = const MeshVertices*;

[[nodiscard]] inline glm::vec3 vertex_position(VertexPositions positions, std::uint32_t mesh,
                                               std::uint32_t vertex) {
  const float* w = positions[mesh].data + std::size_t{vertex} * positions[mesh].stride;
  return {w[0], w[1], w[2]};
}

/// Corner k (0, 1, 2 for a, b, c) of face f.
[[nodiscard]] inline std::uint32_t face_corner(const gpu::Face& f, std::uint32_t k) {
  return k == 0u ? f.a : (k == 1u ? f.b : f.c);
}

/// The three corners of face f, in the order a, b, c.
inline void face_vertices(VertexPositions positions, const gpu::Face& f, glm::vec3 out[3]) {
  out[0] = vertex_position(positions, f.body, f.a);
  out[1] = vertex_position(positions, f.body, f.b);
  out[2] = vertex_position(positions, f.body, f.c);
}

}  // namespace deformcd::collision
