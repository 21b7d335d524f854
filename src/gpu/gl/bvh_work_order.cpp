#include "gpu/gl/bvh_work_order.h"

#include <algorithm>

namespace deformcd::gl {

BvhWorkOrder plan_bvh_work_order(const std::vector<gpu::BvhNode>& nodes,
                                 const std::vector<gpu::BodyBvh>& trees,
                                 const std::vector<gpu::MeshInfo>& meshes, std::size_t face_count) {
  BvhWorkOrder plan;
  plan.leaves.assign(face_count, 0u);
  // Preorder: a node's depth is its parent's + 1, and parents come first.
  std::vector<std::uint32_t> depth(nodes.size(), 0);
  std::vector<std::vector<std::uint32_t>> by_depth;
  for (std::size_t m = 0; m < trees.size(); ++m) {
    const gpu::BodyBvh& t = trees[m];
    std::uint32_t leaf = meshes[m].face_offset;
    for (std::uint32_t i = t.root; i < t.root + t.node_count; ++i) {
      if (i != t.root) depth[i] = depth[nodes[i].parent] + 1;
      if (nodes[i].face != gpu::kBvhInternal) {
        plan.leaves[leaf++] = i;
        continue;
      }
      if (by_depth.size() <= depth[i]) by_depth.resize(depth[i] + 1);
      by_depth[depth[i]].push_back(i);
    }
  }
  for (auto level = by_depth.rbegin(); level != by_depth.rend(); ++level) {
    if (level->empty()) continue;
    std::sort(level->begin(), level->end());
    plan.levels.emplace_back(static_cast<std::uint32_t>(plan.refit_order.size()),
                             static_cast<std::uint32_t>(level->size()));
    plan.refit_order.insert(plan.refit_order.end(), level->begin(), level->end());
  }
  return plan;
}

}  // namespace deformcd::gl
