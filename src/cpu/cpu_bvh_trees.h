#pragma once
// Every body's BVH on the CPU, kept fitted to the deforming surface: the boxes are refitted
// every pass, in parallel across bodies and across the subtrees of a big body, and a body's tree
// is rebuilt from its current shape when refitting has loosened it too much.
//
// When to rebuild: the summed surface area of a tree's internal boxes over its root's
// (collision::bvh_area_ratio) estimates the cost of a query (the surface area heuristic: a
// query box hits a node about in proportion to its area). Right after a build that ratio is
// what the median split does for the current shape; as the body deforms, siblings grow into
// each other and the ratio climbs. A tree is rebuilt when its ratio exceeds kBvhRebuildFactor
// x the ratio right after its last build, and only when it is about to be traversed (a tree
// that is not is only read at its root, which is exact however loose the rest).
//
// Why 1.5: measured on the shipped scenes (2 cores), rebuilding a 5k-face body costs about
// 2 ms, as much as a whole bvh pass in contact, of which traversal is about 60%; at a 1.5x
// looser tree the extra traversal repays a rebuild within a few frames of contact, while a
// factor near 1 would rebuild on every wobble (the ratio moves by a few % as the shipped
// bodies squash and spring back) for no measurable gain. The ratio costs about a tenth of a
// refit, so it is measured every pass.

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/collision/bvh.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/world_state.h"

namespace deformcd::cpu {

using collision::kBvhRebuildFactor;

class BvhTrees {
 public:
  // Takes the trees built at assembly (state.bvh_nodes, body_bvhs) and fits them to
  // state.positions; their area ratios there are the first rebuild references.
  void upload(const WorldState& state);
  // Refits every tree to `positions` and measures its area ratio.
  void refit(const std::vector<glm::vec4>& positions, const std::vector<gpu::Face>& faces);
  // Rebuilds `body`'s tree from `positions` (then refits it) when its area ratio measured by the
  // last refit exceeds kBvhRebuildFactor x the ratio after its last build. Returns whether it did.
  bool rebuild_if_degraded(std::uint32_t body, const std::vector<glm::vec4>& positions,
                           const std::vector<gpu::Face>& faces);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<gpu::Box>& boxes() const { return boxes_; }
  [[nodiscard]] const gpu::BodyBvh& tree(std::uint32_t body) const { return trees_[body]; }
  // The area ratio of `body`'s tree as last refitted, and right after its last build.
  [[nodiscard]] double area_ratio(std::uint32_t body) const { return ratio_[body]; }
  [[nodiscard]] double built_area_ratio(std::uint32_t body) const { return built_ratio_[body]; }
  // Trees rebuilt since upload.
  [[nodiscard]] std::uint64_t rebuild_count() const { return rebuilds_; }

 private:
  void refit_body(std::uint32_t body, const std::vector<glm::vec4>& positions,
                  const std::vector<gpu::Face>& faces);
  void refit_subtree(std::uint32_t node, std::uint32_t count,
                     const std::vector<glm::vec4>& positions, const std::vector<gpu::Face>& faces);

  std::vector<gpu::ObjectInfo> objects_;
  std::vector<gpu::BvhNode> nodes_;  // SSBO 25
  std::vector<gpu::Box> boxes_;      // SSBO 26
  std::vector<gpu::BodyBvh> trees_;  // SSBO 27
  std::vector<double> ratio_;
  std::vector<double> built_ratio_;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace deformcd::cpu
