#include "core/collision/bvh_upkeep.h"

#include <algorithm>
#include <atomic>
#include <string>

#include "deformcd/error.h"

namespace deformcd::collision {

namespace {

// A new generation stamp, unique in the process (1, 2, ...).
std::uint64_t next_generation() {
  static std::atomic<std::uint64_t> last{0};
  return last.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace

void BvhUpkeep::reset(const CollisionData& data, VertexPositions pose) {
  faces_ = data.faces;
  meshes_ = data.meshes;
  nodes_ = data.bvh_nodes;
  trees_ = data.mesh_bvhs;
  rebuilds_ = 0;
  generation_ = next_generation();
  std::vector<gpu::Box> boxes(nodes_.size());
  built_ratio_.assign(trees_.size(), 0.0);
  for (std::uint32_t m = 0; m < trees_.size(); ++m) {
    refit_bvh(nodes_, trees_[m].root, trees_[m].node_count, pose, faces_, boxes);
    built_ratio_[m] = area_ratio(m, boxes);
  }
}

double BvhUpkeep::area_ratio(std::uint32_t mesh, const std::vector<gpu::Box>& boxes) const {
  return bvh_area_ratio(nodes_, trees_[mesh].root, trees_[mesh].node_count, boxes);
}

bool BvhUpkeep::degraded(std::uint32_t mesh, double ratio) const {
  return ratio > kBvhRebuildFactor * built_ratio_[mesh];
}

void BvhUpkeep::rebuild(std::uint32_t mesh, VertexPositions positions,
                        std::vector<gpu::Box>& boxes) {
  gpu::BodyBvh& t = trees_[mesh];
  const gpu::MeshInfo& m = meshes_[mesh];
  // Same faces, so the same node count and range: the new tree replaces the old one in place.
  const std::vector<gpu::BvhNode> rebuilt =
      build_bvh(positions, faces_, m.face_offset, m.face_count, t.root);
  const std::uint32_t depth = bvh_depth(rebuilt, t.root);
  if (depth >= kBvhMaxDepth) {
    throw Error("BVH of mesh " + std::to_string(mesh) + " rebuilt deeper than the traversal stack");
  }
  std::copy(rebuilt.begin(), rebuilt.end(), nodes_.begin() + t.root);
  t.depth = depth;
  refit_bvh(nodes_, t.root, t.node_count, positions, faces_, boxes);
  built_ratio_[mesh] = area_ratio(mesh, boxes);
  ++rebuilds_;
  generation_ = next_generation();
}

}  // namespace deformcd::collision
