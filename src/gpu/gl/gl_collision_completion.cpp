// GlCollision at the frame boundary: complete_pass() reads the counters the last pass left,
// grows the lists that overflowed and reruns the pass, then keeps the BVHs in shape. The lists
// feed each other (box pairs -> candidates -> face pairs): a list after an overflowed one has a
// partial count, so each rerun makes at least the first overflowed list whole, and three reruns
// always settle a pass on unchanged positions.

#include <epoxy/gl.h>

#include <span>
#include <string>

#include "deformcd/error.h"
#include "gl_check.h"
#include "gl_collision.h"

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
  for (int rerun = 0;; ++rerun) {
    const gpu::CollisionCounters found = b.counters.download(0, 1).front();
    if (!overflowed(b, found)) break;
    if (rerun == kMaxReruns) {
      throw Error("GlCollision::complete_pass: the pass still overflowed after " +
                  std::to_string(kMaxReruns) + " reruns (" + std::to_string(found.box_pairs) +
                  " box pairs, " + std::to_string(found.candidates) + " candidates, " +
                  std::to_string(found.face_pairs) + " face pairs; did the positions change?)");
    }
    grow_overflowed(b, found);
    // A pass is deterministic in what it counts (only the slots' order varies): on the same
    // positions, the grown lists hold what overflowed.
    detect(last_method_);
  }
  pass_pending_ = false;
  if (last_method_ == BroadPhase::kBvh) maintain_bvhs(b);
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
  if (lists_box_pairs(last_method_) && found.box_pairs > b.box_pair_capacity) {
    b.box_pair_capacity = grown(found.box_pairs, sizeof(glm::uvec2), "Box Pair List", "SSBO 30");
    b.box_pair_list = Ssbo<glm::uvec2>(b.box_pair_capacity);
  }
  if (lists_candidates(last_method_) && found.candidates > b.candidate_capacity) {
    b.candidate_capacity = grown(found.candidates, sizeof(glm::uvec2), "Candidate Pair", "SSBO 28");
    b.candidates = Ssbo<glm::uvec2>(b.candidate_capacity);
  }
  if (found.face_pairs > b.pair_capacity) {
    b.pair_capacity = grown(found.face_pairs, sizeof(gpu::FacePair), "Face Pair", "SSBO 10");
    b.face_pairs = Ssbo<gpu::FacePair>(b.pair_capacity);
  }
  set_capacity_uniforms(b);
}

void GlCollision::maintain_bvhs(CollisionBuffers& b) {
  if (!rebuilder_->count_pass()) return;
  const std::vector<gpu::Box> boxes = b.bvh_boxes.download(0, b.bvh_node_count);
  const std::vector<std::uint32_t> degraded = rebuilder_->degraded_bodies(boxes);
  if (degraded.empty()) return;
  const std::vector<glm::vec4> positions = download_positions(b);
  for (std::uint32_t body : degraded) {
    rebuilder_->rebuild(body, positions);
    const gpu::BodyBvh& t = rebuilder_->body_bvhs()[body];
    const std::span<const gpu::BvhNode> nodes(rebuilder_->nodes().data() + t.root, t.node_count);
    b.bvh_nodes.upload(nodes, t.root);
    b.body_bvhs.upload(std::span<const gpu::BodyBvh>(&t, 1), body);
  }
  // The depths changed: so did the refit's levels (the internal nodes are as many as before).
  BvhWorkOrder order = plan_bvh_work_order(rebuilder_->nodes(), rebuilder_->body_bvhs(),
                                           rebuilder_->objects(), b.face_count);
  b.bvh_levels.upload(std::span<const std::uint32_t>(order.refit_order));
  b.bvh_leaves.upload(std::span<const std::uint32_t>(order.leaves));
  b.bvh_levels_ranges = std::move(order.levels);
}

std::vector<glm::vec4> GlCollision::download_positions(const CollisionBuffers& b) const {
  std::vector<glm::vec4> positions(b.node_count);
  if (positions.empty()) return positions;
  // The simulation's buffer: detect() checked that it holds node_count positions.
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT));
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, simulation_.gl_position_buffer()));
  DEFORMCD_GL_CHECK(glGetBufferSubData(
      GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(positions.size() * sizeof(glm::vec4)),
      positions.data()));
  return positions;
}

}  // namespace deformcd::gl
