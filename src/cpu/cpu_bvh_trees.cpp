#include "cpu_bvh_trees.h"

#include <algorithm>

#include <tbb/parallel_invoke.h>
#include <glm/common.hpp>

#include "core/collision/bvh.h"
#include "parallel_for.h"

namespace deformcd::cpu {

namespace {

// Subtrees up to this many nodes are refitted on one thread: below it, splitting costs more
// than the boxes (a node's refit is a few loads and six min/max).
constexpr std::uint32_t kSerialRefitNodes = 2048;

}  // namespace

void BvhTrees::upload(const collision::CollisionData& data, collision::VertexPositions pose) {
  upkeep_.reset(data, pose);
  faces_ = data.faces;
  boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
  ratio_.assign(upkeep_.trees().size(), 0.0);
  refit(pose);
}

void BvhTrees::refit(collision::VertexPositions positions) {
  parallel_for(
      ratio_.size(),
      [&](std::size_t mesh) { refit_mesh(static_cast<std::uint32_t>(mesh), positions); }, 1);
}

void BvhTrees::refit_mesh(std::uint32_t mesh, collision::VertexPositions positions) {
  const gpu::BodyBvh& t = upkeep_.tree(mesh);
  refit_subtree(t.root, t.node_count, positions);
  ratio_[mesh] = upkeep_.area_ratio(mesh, boxes_);
}

// Preorder puts a subtree in one range: the node, its left subtree [node + 1, right), then its
// right subtree [right, node + count). The two halves are independent, so they run in parallel
// down to kSerialRefitNodes, and the node's box is their union.
void BvhTrees::refit_subtree(std::uint32_t node, std::uint32_t count,
                             collision::VertexPositions positions) {
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  if (count <= kSerialRefitNodes) {
    collision::refit_bvh(nodes, node, count, positions, faces_, boxes_);
    return;
  }
  const gpu::BvhNode& n = nodes[node];
  tbb::parallel_invoke([&] { refit_subtree(n.left, n.right - n.left, positions); },
                       [&] { refit_subtree(n.right, node + count - n.right, positions); });
  const gpu::Box& l = boxes_[n.left];
  const gpu::Box& r = boxes_[n.right];
  boxes_[node] = {glm::vec4(glm::min(glm::vec3(l.min), glm::vec3(r.min)), 0.0f),
                  glm::vec4(glm::max(glm::vec3(l.max), glm::vec3(r.max)), 0.0f)};
}

bool BvhTrees::rebuild_if_degraded(std::uint32_t mesh, collision::VertexPositions positions) {
  if (!upkeep_.degraded(mesh, ratio_[mesh])) return false;
  upkeep_.rebuild(mesh, positions, boxes_);
  ratio_[mesh] = upkeep_.built_ratio(mesh);
  return true;
}

}  // namespace deformcd::cpu
