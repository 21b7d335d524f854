#pragma once
// Per-vertex reaches and motions for the proximity tests, in the two shapes the searches take
// them: flat lists over every mesh's vertices, mesh 0's first (GlProximity, Detector), and
// per-mesh views into them (CpuProximity); and the host search over a fixture's own trees.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_backend.h"
#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "core/collision/vertex_positions.h"
#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"
#include "gl/sim_test_worlds.h"

namespace deformcd::test {

/// The lists and the per-mesh views into them (re-pointed when copied: a copy's views are its
/// own; call repoint() after resizing a list).
class VertexLists {
 public:
  std::vector<float> reach;          // per vertex of every mesh
  std::vector<glm::vec3> motion;     // per vertex of every mesh, or empty
  std::vector<std::uint32_t> first;  // per mesh: its first vertex in the lists

  VertexLists() = default;
  VertexLists(const VertexLists& other)
      : reach(other.reach), motion(other.motion), first(other.first) {
    repoint();
  }
  VertexLists(VertexLists&&) noexcept = default;  // a moved vector keeps its elements
  VertexLists& operator=(const VertexLists& other) {
    if (this != &other) {
      reach = other.reach;
      motion = other.motion;
      first = other.first;
      repoint();
    }
    return *this;
  }
  VertexLists& operator=(VertexLists&&) noexcept = default;
  ~VertexLists() = default;

  void repoint() {
    reach_of_.clear();
    motion_of_.clear();
    for (const std::uint32_t f : first) {
      reach_of_.push_back(reach.data() + f);
      if (!motion.empty()) motion_of_.push_back({&motion[f].x, 3u});
    }
  }
  [[nodiscard]] collision::VertexReach cpu_reach() const { return reach_of_.data(); }
  [[nodiscard]] collision::VertexPositions cpu_motion() const {
    return motion_of_.empty() ? nullptr : motion_of_.data();
  }
  /// A backend's query on `positions` over `mesh_pairs`, with these lists.
  [[nodiscard]] collision::ProximityQuery query(collision::VertexPositions positions,
                                                std::span<const std::uint32_t> mesh_pairs) const {
    return {.positions = positions,
            .motion = cpu_motion(),
            .reach = cpu_reach(),
            .flat_motion = motion,
            .flat_reach = reach,
            .mesh_pairs = mesh_pairs};
  }

 private:
  std::vector<const float*> reach_of_;              // per mesh, into `reach`
  std::vector<collision::MeshVertices> motion_of_;  // per mesh, into `motion` (empty: none)
};

/// Mesh m's vertices get a reach between 0.5 and 1.5 x reach[m] (deterministic noise, `salt`)
/// and, unless `drift` is empty, the motion drift[m] plus up to `jitter` (m) per component.
inline VertexLists vertex_lists(const collision::CollisionData& data, std::span<const float> reach,
                                std::span<const glm::vec3> drift = {}, float jitter = 0.0f,
                                std::uint32_t salt = 1u) {
  VertexLists out;
  std::uint32_t n = 0;
  for (std::uint32_t m = 0; m < data.mesh_count(); ++m) {
    out.first.push_back(n);
    for (std::uint32_t v = 0; v < data.meshes[m].vertex_count; ++v, ++n) {
      out.reach.push_back(reach[m] * (1.0f + 0.5f * hash_unit(n, salt)));
      if (!drift.empty()) {
        out.motion.push_back(drift[m] + jitter * glm::vec3(hash_unit(n, salt + 1),
                                                           hash_unit(n, salt + 2),
                                                           hash_unit(n, salt + 3)));
      }
    }
  }
  out.repoint();
  return out;
}

/// `data`'s trees (as a fixture uploads them to the GPU), fitted to `pose`.
inline collision::BvhUpkeep fitted_trees(const collision::CollisionData& data,
                                         collision::VertexPositions pose) {
  collision::BvhUpkeep trees;
  trees.reset(data, pose);
  return trees;
}

/// The host search over a fixture's own trees: the list the GL search over the same trees
/// must give, in the same order.
struct HostProximity {
  HostProximity(const collision::CollisionData& data, collision::VertexPositions pose)
      : trees(fitted_trees(data, pose)),
        search(trees, data.mesh_pairs, std::make_shared<cpu::Executor>(2)) {}
  HostProximity(const HostProximity&) = delete;
  HostProximity& operator=(const HostProximity&) = delete;
  ~HostProximity() = default;

  collision::BvhUpkeep trees;
  cpu::CpuProximity search;
};

}  // namespace deformcd::test
