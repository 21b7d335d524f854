#pragma once
// The one BVH upkeep both backends share: every mesh's tree topology, and when to rebuild it.
// The boxes are refitted every pass by the backend (collision::refit_bvh on the CPU,
// bvh_refit*.comp on GL, the same min/max of the same floats); as a mesh deforms, siblings grow
// into each other and queries slow down. The summed surface area of a tree's internal boxes over
// its root's (bvh_area_ratio) estimates the cost of a query (the surface area heuristic); a tree
// is rebuilt, on the host from the current positions, when that ratio exceeds
// kBvhRebuildFactor x the ratio right after its last build. The CPU backend measures it every
// pass (it costs a tenth of a refit) and rebuilds only trees about to be traversed; the GL
// backend reads its boxes back every few passes (GlCollisionOptions::bvh_check_interval).

#include <cstdint>
#include <vector>

#include "core/collision/bvh.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

class BvhUpkeep {
 public:
  /// Takes the trees of `data` (built on `pose`) and records each one's area ratio on `pose`
  /// as its first reference.
  void reset(const CollisionData& data, VertexPositions pose);

  /// Mesh `mesh`'s tree's area ratio with `boxes` (one per node, every mesh's).
  [[nodiscard]] double area_ratio(std::uint32_t mesh, const std::vector<gpu::Box>& boxes) const;
  /// Whether a tree whose area ratio is now `ratio` should be rebuilt.
  [[nodiscard]] bool degraded(std::uint32_t mesh, double ratio) const;
  /// Rebuilds mesh `mesh`'s tree on `positions` in its node range (same faces, same node
  /// count: nothing else moves), refits that range of `boxes` and makes its ratio the new
  /// reference. Throws Error when the new tree is deeper than a traversal stack holds.
  void rebuild(std::uint32_t mesh, VertexPositions positions, std::vector<gpu::Box>& boxes);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  [[nodiscard]] const gpu::BodyBvh& tree(std::uint32_t mesh) const { return trees_[mesh]; }
  [[nodiscard]] const std::vector<gpu::BodyBvh>& trees() const { return trees_; }
  /// The area ratio of mesh `mesh`'s tree right after its last build.
  [[nodiscard]] double built_ratio(std::uint32_t mesh) const { return built_ratio_[mesh]; }
  /// Trees rebuilt since reset.
  [[nodiscard]] std::uint64_t rebuilds() const { return rebuilds_; }
  /// Changes whenever the topology does (reset, rebuild), and differs between any two
  /// topologies of any BvhUpkeep of the process: whoever keeps boxes per node (a proximity
  /// search's swept boxes) knows from it whether they still fit the nodes.
  [[nodiscard]] std::uint64_t generation() const { return generation_; }
  /// The faces and meshes the trees are over (CollisionData's, as reset took them).
  [[nodiscard]] const std::vector<gpu::Face>& faces() const { return faces_; }
  [[nodiscard]] const std::vector<gpu::MeshInfo>& meshes() const { return meshes_; }

 private:
  std::vector<gpu::Face> faces_;
  std::vector<gpu::MeshInfo> meshes_;
  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::BodyBvh> trees_;
  std::vector<double> built_ratio_;
  std::uint64_t rebuilds_ = 0;
  std::uint64_t generation_ = 0;  // 0: no trees yet
};

}  // namespace deformcd::collision
