#pragma once
// The count a box-culling broad phase must reach: face pairs of the collision data's mesh pairs
// whose exact bounding boxes overlap, by testing every such pair.

#include <cstdint>

#include <glm/vec3.hpp>

#include "core/collision/broad_phase.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"

namespace deformcd::test {

/// The bounding box of face `face` (an index over every mesh) at `positions`.
inline gpu::Box face_box(const collision::CollisionData& data, collision::VertexPositions positions,
                         std::uint32_t face) {
  glm::vec3 corners[3];
  collision::face_vertices(positions, data.faces[face], corners);
  gpu::Box b = collision::empty_box();
  for (const glm::vec3& c : corners)
    collision::grow_box(b, c);
  return b;
}

/// Face pairs of data.mesh_pairs whose boxes overlap: what the bvh broad phase hands on. A mesh
/// paired with itself counts each pair of its faces once (face_a < face_b, as the narrow phase
/// keeps it), edge neighbours included (the narrow phase counts them before it skips them).
inline std::uint64_t face_box_overlaps(const collision::CollisionData& data,
                                       collision::VertexPositions positions) {
  std::uint64_t count = 0;
  for (const gpu::BodyPair& pair : data.mesh_pairs) {
    const gpu::MeshInfo& a = data.meshes[pair.a];
    const gpu::MeshInfo& b = data.meshes[pair.b];
    for (std::uint32_t fa = a.face_offset; fa < a.face_offset + a.face_count; ++fa) {
      const gpu::Box box_a = face_box(data, positions, fa);
      for (std::uint32_t fb = b.face_offset; fb < b.face_offset + b.face_count; ++fb) {
        if (pair.a == pair.b && fb <= fa) continue;
        count += collision::boxes_overlap(box_a, face_box(data, positions, fb)) ? 1u : 0u;
      }
    }
  }
  return count;
}

}  // namespace deformcd::test
