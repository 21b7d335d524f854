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
  refit_nodes_.resize(upkeep_.nodes().size());
  make_refit_nodes(0, static_cast<std::uint32_t>(refit_nodes_.size()));
  boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
  refit(pose);
}

void BvhTrees::refit(collision::VertexPositions positions) {
  parallel_for(
      upkeep_.trees().size(),
      [&](std::size_t mesh) { refit_mesh(static_cast<std::uint32_t>(mesh), positions); }, 1);
}

void BvhTrees::make_refit_nodes(std::uint32_t first, std::uint32_t count) {
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  for (std::uint32_t i = first; i < first + count; ++i) {
    const gpu::BvhNode& n = nodes[i];
    if (n.face == gpu::kBvhInternal) {
      refit_nodes_[i] = {n.left, n.right, 0u, gpu::kBvhInternal};
    } else {
      const gpu::Face& f = faces_[n.face];
      refit_nodes_[i] = {f.a, f.b, f.c, f.body};
    }
  }
}

// The loop of collision::refit_bvh (reverse preorder, children first), reading refit_nodes_.
void BvhTrees::refit_range(std::uint32_t first, std::uint32_t count,
                           collision::VertexPositions positions) {
  for (std::uint32_t i = first + count; i-- > first;) {
    const RefitNode& n = refit_nodes_[i];
    gpu::Box b = collision::empty_box();
    if (n.mesh != gpu::kBvhInternal) {
      collision::grow_box(b, collision::vertex_position(positions, n.mesh, n.x));
      collision::grow_box(b, collision::vertex_position(positions, n.mesh, n.y));
      collision::grow_box(b, collision::vertex_position(positions, n.mesh, n.z));
    } else {
      const gpu::Box& l = boxes_[n.x];
      const gpu::Box& r = boxes_[n.y];
      b.min = glm::vec4(glm::min(glm::vec3(l.min), glm::vec3(r.min)), 0.0f);
      b.max = glm::vec4(glm::max(glm::vec3(l.max), glm::vec3(r.max)), 0.0f);
    }
    boxes_[i] = b;
  }
}

void BvhTrees::refit_mesh(std::uint32_t mesh, collision::VertexPositions positions) {
  const gpu::BodyBvh& t = upkeep_.tree(mesh);
  refit_subtree(t.root, t.node_count, positions);
}

// Preorder puts a subtree in one range: the node, its left subtree [node + 1, right), then its
// right subtree [right, node + count). The two halves are independent, so they run in parallel
// down to kSerialRefitNodes, and the node's box is their union.
void BvhTrees::refit_subtree(std::uint32_t node, std::uint32_t count,
                             collision::VertexPositions positions) {
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  if (count <= kSerialRefitNodes) {
    refit_range(node, count, positions);
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

std::uint32_t BvhTrees::rebuild_degraded(const std::vector<std::uint8_t>& traversed,
                                         collision::VertexPositions positions) {
  degraded_.assign(traversed.size(), 0u);
  parallel_for(
      traversed.size(),
      [&](std::size_t m) {
        const auto mesh = static_cast<std::uint32_t>(m);
        if (traversed[m] != 0u && upkeep_.degraded(mesh, area_ratio(mesh))) degraded_[m] = 1u;
      },
      1);
  std::uint32_t rebuilt = 0;
  for (std::uint32_t mesh = 0; mesh < degraded_.size(); ++mesh) {
    if (degraded_[mesh] == 0u) continue;
    upkeep_.rebuild(mesh, positions, boxes_);
    make_refit_nodes(upkeep_.tree(mesh).root, upkeep_.tree(mesh).node_count);
    ++rebuilt;
  }
  return rebuilt;
}

}  // namespace deformcd::cpu
