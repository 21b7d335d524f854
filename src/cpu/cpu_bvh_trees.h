#pragma once
// Every mesh's BVH on the CPU, kept fitted to the deforming surface: the boxes are refitted
// every pass, in parallel across meshes and across the subtrees of a big mesh, and a mesh's
// tree is rebuilt from its current shape when refitting has loosened it too much. When to
// rebuild is the shared policy of collision::BvhUpkeep (core/collision/bvh_upkeep.h), which
// also holds the trees' topology; the CPU measures a tree's area ratio (a pass over its boxes,
// 9 % of a bvh pass at 50,000 faces per body) only when the tree is about to be traversed, and
// rebuilds it then if it has degraded.

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
  // Refits every tree to `positions`.
  void refit(collision::VertexPositions positions);
  // Rebuilds, from `positions`, the tree of every mesh m with traversed[m] != 0 whose area ratio,
  // measured now, says it has degraded (collision::BvhUpkeep::degraded): the ratios are measured
  // in parallel across the meshes, the rebuilds one after the other. Returns how many it rebuilt.
  std::uint32_t rebuild_degraded(const std::vector<std::uint8_t>& traversed,
                                 collision::VertexPositions positions);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return upkeep_.nodes(); }
  [[nodiscard]] const std::vector<gpu::Box>& boxes() const { return boxes_; }
  [[nodiscard]] const gpu::BodyBvh& tree(std::uint32_t mesh) const { return upkeep_.tree(mesh); }
  // The area ratio of `mesh`'s tree as last refitted (measured by the call), and right after its
  // last build.
  [[nodiscard]] double area_ratio(std::uint32_t mesh) const {
    return upkeep_.area_ratio(mesh, boxes_);
  }
  [[nodiscard]] double built_area_ratio(std::uint32_t mesh) const {
    return upkeep_.built_ratio(mesh);
  }
  // Trees rebuilt since upload.
  [[nodiscard]] std::uint64_t rebuild_count() const { return upkeep_.rebuilds(); }

 private:
  // One node as the refit reads it, in the nodes' order: a leaf's face corners (vertex indices
  // of its mesh) and mesh, or an internal node's children and kBvhInternal. Made from the nodes
  // and faces on upload and on a rebuild, so that a refit streams one 16-byte array instead of
  // reading each node and then, at a leaf, its face elsewhere (at 50,000 faces per body the
  // trees and faces far exceed the caches: the refit was half of a bvh pass).
  struct RefitNode {
    std::uint32_t x;     // left child, or corner a
    std::uint32_t y;     // right child, or corner b
    std::uint32_t z;     // corner c
    std::uint32_t mesh;  // kBvhInternal for an internal node
  };

  void make_refit_nodes(std::uint32_t first, std::uint32_t count);
  // collision::refit_bvh over refit_nodes_: the same boxes, bit for bit.
  void refit_range(std::uint32_t first, std::uint32_t count, collision::VertexPositions positions);
  void refit_mesh(std::uint32_t mesh, collision::VertexPositions positions);
  void refit_subtree(std::uint32_t node, std::uint32_t count, collision::VertexPositions positions);

  collision::BvhUpkeep upkeep_;
  std::vector<gpu::Face> faces_;
  std::vector<RefitNode> refit_nodes_;  // per node
  std::vector<gpu::Box> boxes_;         // per node
  std::vector<std::uint8_t> degraded_;  // per mesh, rebuild_degraded's
};

}  // namespace deformcd::cpu
