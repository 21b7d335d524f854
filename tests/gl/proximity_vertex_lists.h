#pragma once
// Per-vertex reaches and motions for the proximity tests, in the two shapes the searches take
// them: flat lists over every mesh's vertices, mesh 0's first (GlProximity, Detector), and
// per-mesh views into them (CpuProximity).

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "core/collision/vertex_positions.h"
#include "sim_test_worlds.h"

namespace deformcd::test {

struct VertexLists {
  std::vector<float> reach;                        // per vertex of every mesh
  std::vector<glm::vec3> motion;                   // per vertex of every mesh, or empty
  std::vector<const float*> reach_of;              // per mesh, into `reach`
  std::vector<collision::MeshVertices> motion_of;  // per mesh, into `motion` (empty: none)

  [[nodiscard]] collision::VertexReach cpu_reach() const { return reach_of.data(); }
  [[nodiscard]] collision::VertexPositions cpu_motion() const {
    return motion_of.empty() ? nullptr : motion_of.data();
  }
};

inline void point_views(const collision::CollisionData& data, VertexLists& lists);

/// Mesh m's vertices get a reach between 0.5 and 1.5 x reach[m] (deterministic noise, `salt`)
/// and, unless `drift` is empty, the motion drift[m] plus up to `jitter` (m) per component.
inline VertexLists vertex_lists(const collision::CollisionData& data, std::span<const float> reach,
                                std::span<const glm::vec3> drift = {}, float jitter = 0.0f,
                                std::uint32_t salt = 1u) {
  VertexLists out;
  std::uint32_t n = 0;
  for (std::uint32_t m = 0; m < data.mesh_count(); ++m) {
    for (std::uint32_t v = 0; v < data.meshes[m].vertex_count; ++v, ++n) {
      out.reach.push_back(reach[m] * (1.0f + 0.5f * hash_unit(n, salt)));
      if (!drift.empty()) {
        out.motion.push_back(drift[m] + jitter * glm::vec3(hash_unit(n, salt + 1),
                                                           hash_unit(n, salt + 2),
                                                           hash_unit(n, salt + 3)));
      }
    }
  }
  point_views(data, out);
  return out;
}

/// Points reach_of and motion_of into `lists` (after its vectors changed).
inline void point_views(const collision::CollisionData& data, VertexLists& lists) {
  lists.reach_of.clear();
  lists.motion_of.clear();
  std::size_t first = 0;
  for (std::uint32_t m = 0; m < data.mesh_count(); ++m) {
    lists.reach_of.push_back(lists.reach.data() + first);
    if (!lists.motion.empty()) lists.motion_of.push_back({&lists.motion[first].x, 3u});
    first += data.meshes[m].vertex_count;
  }
}

}  // namespace deformcd::test
