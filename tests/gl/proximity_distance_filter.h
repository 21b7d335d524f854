#pragma once
// The GL proximity search still mirrors only the box stage of emit_face_pair_candidates
// (src/core/collision/proximity.h), without the vertices' motion and the distance filter the
// CPU search applies after it: its list, filtered here on the host with the CPU's own test,
// must be the CPU's list (with no motion).

#include <algorithm>
#include <span>
#include <vector>

#include "core/collision/collision_data.h"
#include "core/collision/primitive_distance.h"
#include "core/collision/proximity.h"

namespace deformcd::test {

/// One reach per mesh spread over its vertices, as CpuProximity::find takes them.
struct ReachPerVertex {
  std::vector<std::vector<float>> values;
  std::vector<const float*> meshes;
  [[nodiscard]] collision::VertexReach get() const { return meshes.data(); }
};

inline ReachPerVertex reach_per_vertex(const collision::CollisionData& data,
                                       std::span<const float> reach) {
  ReachPerVertex out;
  for (std::uint32_t m = 0; m < data.mesh_count(); ++m)
    out.values.emplace_back(data.meshes[m].vertex_count, reach[m]);
  for (const std::vector<float>& v : out.values)
    out.meshes.push_back(v.data());
  return out;
}

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
