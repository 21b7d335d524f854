#pragma once
// Every mesh's BVH on the CPU, kept fitted to the deforming surface: the boxes are refitted
// every pass, in parallel across meshes and across the subtrees of a big mesh, and a mesh's
// tree is rebuilt from its current shape when refitting has loosened it too much. When to
// rebuild is the shared policy of collision::BvhUpkeep (core/collision/bvh_upkeep.h), which
// also holds the trees' topology; the CPU measures each tree's area ratio every pass (about a
// tenth of a refit) and rebuilds a degraded tree only when it is about to be traversed.

#include <cstdint>
#include <vector>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

class BvhTrees {
 public:
  // Takes the trees of `data` (built on `pose`) and fits them to it.
  void upload(const collision::CollisionData& data, collision::VertexPositions pose);
  // Refits every tree to `positions` and measures its area ratio.
  void refit(collision::VertexPositions positions);
  // Rebuilds `mesh`'s tree from `positions` when the ratio measured by the last refit says it
  // has degraded (collision::BvhUpkeep::degraded). Returns whether it did.
  bool rebuild_if_degraded(std::uint32_t mesh, collision::VertexPositions positions);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return upkeep_.nodes(); }
  [[nodiscard]] const std::vector<gpu::Box>& boxes() const { return boxes_; }
  [[nodiscard]] const gpu::BodyBvh& tree(std::uint32_t mesh) const { return upkeep_.tree(mesh); }
  // The area ratio of `mesh`'s tree as last refitted, and right after its last build.
  [[nodiscard]] double area_ratio(std::uint32_t mesh) const { return ratio_[mesh]; }
  [[nodiscard]] double built_area_ratio(std::uint32_t mesh) const {
    return upkeep_.built_ratio(mesh);
  }
  // Trees rebuilt since upload.
  [[nodiscard]] std::uint64_t rebuild_count() const { return upkeep_.rebuilds(); }

 private:
  void refit_mesh(std::uint32_t mesh, collision::VertexPositions positions);
  void refit_subtree(std::uint32_t node, std::uint32_t count, collision::VertexPositions positions);

  collision::BvhUpkeep upkeep_;
  std::vector<gpu::Face> faces_;
  std::vector<gpu::Box> boxes_;  // SSBO 26
  std::vector<double> ratio_;
};

}  // namespace deformcd::cpu
