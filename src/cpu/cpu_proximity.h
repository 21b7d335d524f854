#pragma once
// Proximity candidates on the CPU (issue 12): for each mesh pair a detector tests, the
// vertex-face and edge-edge pairs whose boxes come within the two meshes' reaches, found
// through a BVH per mesh of its own (built on the first search, refitted on every one, rebuilt
// by the shared upkeep rule when deformation has loosened it). Faces run in parallel, each into
// its own list; the lists are joined in face order and sorted, so the result does not depend on
// the thread count.

#include <memory>
#include <span>
#include <vector>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "executor.h"

namespace deformcd::cpu {

class CpuProximity {
 public:
  /// Over the meshes and mesh pairs of `data` (its hierarchies are not needed).
  CpuProximity(const collision::CollisionData& data, std::shared_ptr<Executor> executor);

  /// The candidates on `positions` whose boxes, swept along drift[mesh_a] - drift[mesh_b], come
  /// within reach[mesh_a] + reach[mesh_b] (one reach, >= 0, and one drift per mesh), sorted.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find(
      collision::VertexPositions positions, std::span<const float> reach,
      std::span<const glm::vec3> drift);

 private:
  void refit(collision::VertexPositions positions);

  collision::CollisionData data_;
  std::vector<std::uint32_t> owners_;
  collision::BvhUpkeep upkeep_;
  std::vector<gpu::Box> boxes_;
  bool built_ = false;
  std::shared_ptr<Executor> executor_;
};

}  // namespace deformcd::cpu
