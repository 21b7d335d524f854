// GlCollision at the frame boundary: complete_pass() reads the counters the last pass left,
// grows the lists that overflowed and reruns the pass, then keeps the BVHs in shape. The lists
// feed each other (box pairs -> candidates -> face pairs): a list after an overflowed one has a
// partial count, so each rerun makes at least the first overflowed list whole, and three reruns
// always settle a pass on unchanged positions.

#include <epoxy/gl.h>

#include <optional>
#include <span>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/gl_collision.h"

namespace deformcd::gl {

namespace {

constexpr int kMaxReruns = 3;

// Only octree-compact stores its box pairs, and only it and bvh their candidates: the other
// methods count the same things without a list that could overflow.
bool lists_box_pairs(BroadPhase method) {
  return method == BroadPhase::kOctreeCompact;
}
bool lists_candidates(BroadPhase method) {
  return method == BroadPhase::kOctreeCompact || method == BroadPhase::kBvh;
}

}  // namespace

void GlCollision::complete_pass() {
  if (!pass_pending_) return;
  CollisionBuffers& b = buffers("complete_pass");
  try {
    for (int rerun = 0;; ++rerun) {
      const gpu::CollisionCounters found = b.counters.download(0, 1).front();
      if (!overflowed(b, found)) break;
      if (rerun == kMaxReruns) {
        throw Error("GlCollision::complete_pass: the pass still overflowed after " +
                    std::to_string(kMaxReruns) + " reruns (" + std::to_string(found.box_pairs) +
                    " box pairs, " + std::to_string(found.candidates) + " candidates, " +
                    std::to_string(found.face_pairs) +
                    " face pairs; did the positions in a GL buffer read in place change?)");
      }
      grow_overflowed(b, found);
      // A pass is deterministic in what it counts (only the slots' order varies): on the same
      // (staged) positions, the grown lists hold what overflowed.
      run_pass(last_method_, b);
    }
  } catch (const Error& e) {
    // The pass overwrote the previous results and its own lists are partial: nothing whole is
    // left to read until the next pass. The buffers stay as they are (grow_overflowed replaces
    // none when it fails), so the next detect() runs as if this pass had not been.
    pass_pending_ = false;
    lost_pass_ = LostPass{e.what(), dynamic_cast<const GlError*>(&e) != nullptr};
    throw;
  }
  pass_pending_ = false;
  if (last_method_ == BroadPhase::kBvh) maintain_bvhs(b);
}

void GlCollision::require_results(const char* operation) const {
  if (!lost_pass_) return;
  const std::string message = std::string("GlCollision::") + operation +
                              ": the last pass's results are lost (" + lost_pass_->why +
                              "); the next detect() runs a new pass";
  if (lost_pass_->gl) throw GlError(message);
  throw Error(message);
}

bool GlCollision::overflowed(const CollisionBuffers& b, const gpu::CollisionCounters& found) const {
  return (lists_box_pairs(last_method_) && found.box_pairs > b.box_pair_capacity) ||
         (lists_candidates(last_method_) && found.candidates > b.candidate_capacity) ||
         found.face_pairs > b.pair_capacity;
}

void GlCollision::grow_overflowed(CollisionBuffers& b, const gpu::CollisionCounters& found) {
  // Half again as many: a few more next frame do not cost another rerun. A count after an
  // overflowed list is a lower bound, so growing to it is never too much.
  const auto grown = [this](std::uint32_t count, std::uint64_t element_bytes, const char* name,
                            const char* binding) {
    const std::uint64_t most = most_elements(element_bytes);
    if (count > most) {
      throw GlError("GL collision: a pass needs " + std::to_string(count) + " entries of " + name +
                    " (" + binding + "), more than it can hold under " + std::string(limit_name()) +
                    " (" + std::to_string(max_buffer_bytes_) + " bytes: " + std::to_string(most) +
                    " of " + std::to_string(element_bytes) + " bytes)");
    }
    return static_cast<std::uint32_t>(std::min<std::uint64_t>(most, count + count / 2));
  };
  // Every grown list is allocated before any is replaced: when the driver refuses one, the
  // lists and their capacities (the shaders' uniforms) stay as they were, consistent.
  const auto allocate_grown = [](std::uint32_t capacity, std::uint32_t slots, std::uint32_t count,
                                 const BufferLabel& label, auto element) {
    try {
      return allocate<decltype(element)>(slots, label);
    } catch (const GlError& e) {
      throw GlError(std::string(e.what()) + "; growing it from " + std::to_string(capacity) +
                    " entries after a pass found " + std::to_string(count) +
                    ": the lists keep their size");
    }
  };
  std::optional<Ssbo<glm::uvec2>> box_pairs;
  std::optional<Ssbo<glm::uvec2>> candidates;
  std::optional<Ssbo<gpu::FacePair>> face_pairs;
  std::uint32_t box_pair_capacity = b.box_pair_capacity;
  std::uint32_t candidate_capacity = b.candidate_capacity;
  std::uint32_t pair_capacity = b.pair_capacity;
  if (lists_box_pairs(last_method_) && found.box_pairs > b.box_pair_capacity) {
    box_pair_capacity = grown(found.box_pairs, sizeof(glm::uvec2), "Box Pair List", "SSBO 30");
    box_pairs.emplace(allocate_grown(b.box_pair_capacity, box_pair_capacity, found.box_pairs,
                                     {"GL collision", "Box Pair List", kBoxPairListBinding},
                                     glm::uvec2{}));
  }
  if (lists_candidates(last_method_) && found.candidates > b.candidate_capacity) {
    candidate_capacity = grown(found.candidates, sizeof(glm::uvec2), "Candidate Pair", "SSBO 28");
    candidates.emplace(allocate_grown(b.candidate_capacity, candidate_capacity, found.candidates,
                                      {"GL collision", "Candidate Pair", gpu::kCandidatePair},
                                      glm::uvec2{}));
  }
  if (found.face_pairs > b.pair_capacity) {
    pair_capacity = grown(found.face_pairs, sizeof(gpu::FacePair), "Face Pair", "SSBO 10");
    face_pairs.emplace(allocate_grown(b.pair_capacity, pair_capacity, found.face_pairs,
                                      {"GL collision", "Face Pair", gpu::kFacePair},
                                      gpu::FacePair{}));
  }
  if (box_pairs) b.box_pair_list = std::move(*box_pairs);
  if (candidates) b.candidates = std::move(*candidates);
  if (face_pairs) b.face_pairs = std::move(*face_pairs);
  b.box_pair_capacity = box_pair_capacity;
  b.candidate_capacity = candidate_capacity;
  b.pair_capacity = pair_capacity;
  set_capacity_uniforms(b);
}

void GlCollision::maintain_bvhs(CollisionBuffers& b) {
  bvh_passes_ = (bvh_passes_ + 1) % bvh_check_interval_;
  if (bvh_passes_ != 0) return;
  std::vector<gpu::Box> boxes = b.bvh_boxes.download(0, b.bvh_node_count);
  bool rebuilt = false;
  for (std::uint32_t m = 0; m < meshes_.size(); ++m) {
    if (!upkeep_.degraded(m, upkeep_.area_ratio(m, boxes))) continue;
    // The pass's positions (the staged ones): those the boxes were refitted to.
    const std::vector<glm::vec3> positions = staging_.read_staged(m);
    std::vector<collision::MeshVertices> pose(meshes_.size());
    pose[m] = {&positions[0].x, 3u};
    upkeep_.rebuild(m, pose.data(), boxes);
    const gpu::BodyBvh& t = upkeep_.tree(m);
    b.bvh_nodes.upload(std::span<const gpu::BvhNode>(upkeep_.nodes().data() + t.root, t.node_count),
                       t.root);
    b.mesh_bvhs.upload(std::span<const gpu::BodyBvh>(&t, 1), m);
    rebuilt = true;
  }
  if (!rebuilt) return;
  // The depths changed: so did the refit's levels (the internal nodes are as many as before).
  BvhWorkOrder order = plan_bvh_work_order(upkeep_.nodes(), upkeep_.trees(), meshes_, b.face_count);
  b.bvh_levels.upload(std::span<const std::uint32_t>(order.refit_order));
  b.bvh_leaves.upload(std::span<const std::uint32_t>(order.leaves));
  b.bvh_levels_ranges = std::move(order.levels);
}

}  // namespace deformcd::gl
