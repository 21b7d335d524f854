#include "cpu_bvh_trees.h"

#include <algorithm>

#include <tbb/parallel_invoke.h>

#include "core/collision/bvh.h"
#include "deformcd/error.h"
#include "parallel_for.h"

namespace deformcd::cpu {

namespace {

// Subtrees up to this many nodes are refitted on one thread: below it, splitting costs more
// than the boxes (a node's refit is a few loads and six min/max).
constexpr std::uint32_t kSerialRefitNodes = 2048;

}  // namespace

void BvhTrees::upload(const WorldState& state) {
  objects_ = state.objects;
  nodes_ = state.bvh_nodes;
  trees_ = state.body_bvhs;
  boxes_.assign(nodes_.size(), gpu::Box{});
  ratio_.assign(trees_.size(), 0.0);
  rebuilds_ = 0;
  refit(state.positions, state.faces);
  built_ratio_ = ratio_;
}

void BvhTrees::refit(const std::vector<glm::vec4>& positions, const std::vector<gpu::Face>& faces) {
  parallel_for(
      trees_.size(),
      [&](std::size_t body) { refit_body(static_cast<std::uint32_t>(body), positions, faces); }, 1);
}

void BvhTrees::refit_body(std::uint32_t body, const std::vector<glm::vec4>& positions,
                          const std::vector<gpu::Face>& faces) {
  const gpu::BodyBvh& t = trees_[body];
  refit_subtree(t.root, t.node_count, positions, faces);
  ratio_[body] = collision::bvh_area_ratio(nodes_, t.root, t.node_count, boxes_);
}

// Preorder puts a subtree in one range: the node, its left subtree [node + 1, right), then its
// right subtree [right, node + count). The two halves are independent, so they run in parallel
// down to kSerialRefitNodes, and the node's box is their union.
void BvhTrees::refit_subtree(std::uint32_t node, std::uint32_t count,
                             const std::vector<glm::vec4>& positions,
                             const std::vector<gpu::Face>& faces) {
  if (count <= kSerialRefitNodes) {
    collision::refit_bvh(nodes_, node, count, positions, faces, boxes_);
    return;
  }
  const gpu::BvhNode& n = nodes_[node];
  tbb::parallel_invoke([&] { refit_subtree(n.left, n.right - n.left, positions, faces); },
                       [&] { refit_subtree(n.right, node + count - n.right, positions, faces); });
  const gpu::Box& l = boxes_[n.left];
  const gpu::Box& r = boxes_[n.right];
  boxes_[node] = {glm::vec4(glm::min(glm::vec3(l.min), glm::vec3(r.min)), 0.0f),
                  glm::vec4(glm::max(glm::vec3(l.max), glm::vec3(r.max)), 0.0f)};
}

bool BvhTrees::rebuild_if_degraded(std::uint32_t body, const std::vector<glm::vec4>& positions,
                                   const std::vector<gpu::Face>& faces) {
  if (!(ratio_[body] > kBvhRebuildFactor * built_ratio_[body])) return false;
  gpu::BodyBvh& t = trees_[body];
  const gpu::ObjectInfo& o = objects_[body];
  // Same faces, so the same node count and range: the new tree replaces the old one in place.
  const std::vector<gpu::BvhNode> rebuilt =
      collision::build_bvh(positions, faces, o.face_offset, o.face_count, t.root);
  const std::uint32_t depth = collision::bvh_depth(rebuilt, t.root);
  if (depth >= collision::kBvhMaxDepth) {
    throw Error("BVH of body " + std::to_string(body) + " rebuilt deeper than the traversal stack");
  }
  std::copy(rebuilt.begin(), rebuilt.end(), nodes_.begin() + t.root);
  t.depth = depth;
  refit_body(body, positions, faces);
  built_ratio_[body] = ratio_[body];
  ++rebuilds_;
  return true;
}

}  // namespace deformcd::cpu
