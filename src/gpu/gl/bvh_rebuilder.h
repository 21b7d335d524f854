#pragma once
// When and how GlCollision rebuilds a body's BVH (the bvh broad phase). The trees' topology is
// built once on the rest pose (WorldState::bvh_nodes) and only refitted on the GPU each pass;
// as a body deforms, siblings' boxes come to overlap and queries slow down. Every
// `check_interval` completed passes the caller reads the refitted boxes back and asks which
// bodies have degraded: those whose area ratio (collision::bvh_area_ratio) exceeds
// kBvhRebuildFactor x the ratio right after their last build. Their trees are rebuilt on the
// host from the current positions (collision::build_bvh, same node range, so nothing else
// moves) for the caller to upload. No GL here.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/collision/bvh.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/world_state.h"

namespace deformcd::gl {

using collision::kBvhRebuildFactor;

class BvhRebuilder {
 public:
  // Takes the trees, faces and objects of `state`, and the ratio of each tree refitted to
  // state.positions (the positions it was built on). Throws Error for check_interval 0.
  BvhRebuilder(const WorldState& state, std::uint32_t check_interval);

  // Counts a completed bvh pass; true on every check_interval-th, when the caller should call
  // degraded_bodies with the pass's refitted boxes.
  [[nodiscard]] bool count_pass();
  // The bodies whose trees, with `boxes` (one per node, global indices), have degraded past
  // the threshold, in increasing order.
  [[nodiscard]] std::vector<std::uint32_t> degraded_bodies(
      const std::vector<gpu::Box>& boxes) const;
  // Rebuilds body `body`'s tree on `positions` (every node's), in its node range, and resets its
  // build ratio. Throws Error when the new tree is deeper than the traversal stack.
  void rebuild(std::uint32_t body, const std::vector<glm::vec4>& positions);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<gpu::BodyBvh>& body_bvhs() const { return body_bvhs_; }
  [[nodiscard]] const std::vector<gpu::ObjectInfo>& objects() const { return objects_; }
  // The area ratio of each body's tree right after its last build.
  [[nodiscard]] const std::vector<double>& build_ratios() const { return build_ratios_; }
  // Trees rebuilt since construction.
  [[nodiscard]] std::uint32_t rebuilds() const { return rebuilds_; }

 private:
  [[nodiscard]] double ratio_on(std::uint32_t body, const std::vector<glm::vec4>& positions) const;

  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::BodyBvh> body_bvhs_;
  std::vector<gpu::Face> faces_;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<double> build_ratios_;
  std::uint32_t check_interval_ = 1;
  std::uint32_t passes_ = 0;
  std::uint32_t rebuilds_ = 0;
};

}  // namespace deformcd::gl
