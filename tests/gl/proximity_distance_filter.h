#pragma once
// The GL proximity search still mirrors only the box stage of emit_face_pair_candidates
// (src/core/collision/proximity.h), without the vertices' motion and the distance filter the
// CPU search applies after it: its list, filtered here on the host with the CPU's own test,
// must be the CPU's list (with no motion).

#include <algorithm>
#include <span>
#include <vector>

#include "core/collision/primitive_distance.h"
#include "core/collision/proximity.h"

namespace deformcd::test {

inline std::vector<collision::ProximityCandidate> within_reach(
    std::vector<collision::ProximityCandidate> found, collision::VertexPositions positions,
    std::span<const float> reach) {
  std::erase_if(found, [&](const collision::ProximityCandidate& c) {
    const std::uint32_t first_b = c.kind == gpu::kContactEdgeEdge ? 2u : 1u;
    glm::vec3 x[4];
    for (std::uint32_t k = 0; k < 4u; ++k)
      x[k] =
          collision::vertex_position(positions, k < first_b ? c.mesh_a : c.mesh_b, c.vertices[k]);
    return !collision::primitives_within(c.kind, x, 0.0f, reach[c.mesh_a] + reach[c.mesh_b]);
  });
  return found;
}

}  // namespace deformcd::test
