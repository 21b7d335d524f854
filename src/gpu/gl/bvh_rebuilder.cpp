#include "bvh_rebuilder.h"

#include <algorithm>
#include <string>

#include "core/collision/bvh.h"
#include "deformcd/error.h"

namespace deformcd::gl {

BvhRebuilder::BvhRebuilder(const WorldState& state, std::uint32_t check_interval)
    : nodes_(state.bvh_nodes),
      body_bvhs_(state.body_bvhs),
      faces_(state.faces),
      objects_(state.objects),
      check_interval_(check_interval) {
  if (check_interval == 0) throw Error("GlCollisionOptions::bvh_check_interval must be positive");
  std::vector<gpu::Box> boxes(nodes_.size());
  for (const gpu::BodyBvh& t : body_bvhs_) {
    collision::refit_bvh(nodes_, t.root, t.node_count, state.positions, faces_, boxes);
    build_ratios_.push_back(collision::bvh_area_ratio(nodes_, t.root, t.node_count, boxes));
  }
}

bool BvhRebuilder::count_pass() {
  passes_ = (passes_ + 1) % check_interval_;
  return passes_ == 0;
}

std::vector<std::uint32_t> BvhRebuilder::degraded_bodies(const std::vector<gpu::Box>& boxes) const {
  std::vector<std::uint32_t> degraded;
  for (std::uint32_t b = 0; b < body_bvhs_.size(); ++b) {
    const gpu::BodyBvh& t = body_bvhs_[b];
    const double ratio = collision::bvh_area_ratio(nodes_, t.root, t.node_count, boxes);
    if (ratio > kBvhRebuildFactor * build_ratios_[b]) degraded.push_back(b);
  }
  return degraded;
}

void BvhRebuilder::rebuild(std::uint32_t body, const std::vector<glm::vec4>& positions) {
  const gpu::ObjectInfo& o = objects_[body];
  gpu::BodyBvh& t = body_bvhs_[body];
  std::vector<gpu::BvhNode> tree =
      collision::build_bvh(positions, faces_, o.face_offset, o.face_count, t.root);
  const std::uint32_t depth = collision::bvh_depth(tree, t.root);
  if (depth >= collision::kBvhMaxDepth) {
    throw Error("rebuilding body " + std::to_string(body) + "'s BVH gave depth " +
                std::to_string(depth) + ", deeper than the traversal stack (" +
                std::to_string(collision::kBvhMaxDepth) + ")");
  }
  std::copy(tree.begin(), tree.end(), nodes_.begin() + t.root);
  t.depth = depth;
  build_ratios_[body] = ratio_on(body, positions);
  ++rebuilds_;
}

double BvhRebuilder::ratio_on(std::uint32_t body, const std::vector<glm::vec4>& positions) const {
  const gpu::BodyBvh& t = body_bvhs_[body];
  std::vector<gpu::Box> boxes(nodes_.size());
  collision::refit_bvh(nodes_, t.root, t.node_count, positions, faces_, boxes);
  return collision::bvh_area_ratio(nodes_, t.root, t.node_count, boxes);
}

}  // namespace deformcd::gl
