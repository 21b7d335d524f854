#include "cpu_contact_response.h"

#include <algorithm>
#include <atomic>
#include <utility>

#include "deformcd/error.h"
#include "parallel_for.h"

namespace deformcd::cpu {

CpuContactResponse::CpuContactResponse(SimulationState& state, std::shared_ptr<Executor> executor)
    : state_(state), executor_(std::move(executor)) {}

void CpuContactResponse::take(const response::FrameConstraints& constraints) {
  constraints_ = &constraints;
  // Not cleared: a projection writes every slot of the constraints it solves and reads no other.
  corrections_.resize(8u * constraints_->pairs.size());
  impulses_.resize(constraints_->pairs.size());  // reset by each substep's first iteration
  active_.assign(constraints_->pairs.size(), 0u);
  acting_.clear();
}

void CpuContactResponse::begin_frame(const response::FrameConstraints& constraints) {
  take(constraints);
  const std::size_t nodes = state_.positions.size();
  frame_start_.resize(nodes);
  deviation_.assign(nodes, 0.0f);
  counts_.assign(nodes, 0u);
  executor_->run([&] {
    parallel_for(nodes, [&](std::size_t i) {
      frame_start_[i] = glm::vec4(glm::vec3(state_.positions[i]), constraints_->node_motion[i].w);
    });
  });
}

void CpuContactResponse::update_frame(const response::FrameConstraints& constraints) {
  take(constraints);
  for (std::size_t i = 0; i < frame_start_.size(); ++i)
    frame_start_[i].w = constraints_->node_motion[i].w;
}

bool CpuContactResponse::project(const response::ContactConstants& k, int iterations) {
  if (constraints_ == nullptr) throw Error("CpuContactResponse::project before begin_frame()");
  std::atomic<bool> any_strayed{false};  // an OR: the same whatever the order
  const std::vector<gpu::ContactPair>& pairs = constraints_->pairs;
  const std::size_t nodes = state_.positions.size();
  executor_->run([&] {
    // Deviation pass, activity pass (only awake constraints look at their geometry), count,
    // then per iteration the solve and node passes: each writes only its own element's slots,
    // and each node reads its own list in order.
    parallel_for(nodes, [&](std::size_t i) {
      deviation_[i] = response::path_deviation(glm::vec3(state_.positions[i]), frame_start_[i],
                                               constraints_->node_motion[i], k.elapsed);
    });
    parallel_for(
        pairs.size(),
        [&](std::size_t p) {
          const gpu::ContactPair& pair = pairs[p];
          const float deviation[4] = {deviation_[pair.nodes[0]], deviation_[pair.nodes[1]],
                                      deviation_[pair.nodes[2]], deviation_[pair.nodes[3]]};
          bool active = response::contact_awake(pair, deviation, k.elapsed);
          if (active) {
            const glm::vec4 x[4] = {
                state_.positions[pair.nodes[0]], state_.positions[pair.nodes[1]],
                state_.positions[pair.nodes[2]], state_.positions[pair.nodes[3]]};
            active = response::contact_active(pair, x);
          }
          active_[p] = active ? 1u : 0u;
        },
        1024);
    // The count pass, summed from the compacted list: the integer counts do not depend on the
    // order, and equal the GL count pass's over each node's list.
    acting_.clear();
    for (std::uint32_t p = 0; p < pairs.size(); ++p)
      if (active_[p] != 0u) acting_.push_back(p);
    std::fill(counts_.begin(), counts_.end(), 0u);
    for (const std::uint32_t p : acting_)
      for (const std::uint32_t n : pairs[p].nodes)
        ++counts_[n];
    touched_.clear();
    active_offset_.resize(nodes + 1u);
    std::uint32_t slots = 0;
    for (std::uint32_t i = 0; i < nodes; ++i) {
      active_offset_[i] = slots;
      slots += counts_[i];
      if (counts_[i] != 0u) touched_.push_back(i);
    }
    active_offset_[nodes] = slots;
    // Each node's active slots, ascending (constraints in order, corners in order): its list's
    // order without the inactive slots, so the sums are the GL node pass's, without walking
    // the slots of the many candidates that do not act.
    active_slots_.resize(slots);
    cursor_.assign(active_offset_.begin(), active_offset_.end() - 1);
    for (const std::uint32_t p : acting_)
      for (std::uint32_t corner = 0; corner < 4u; ++corner)
        active_slots_[cursor_[pairs[p].nodes[corner]]++] = 4u * p + corner;
    for (int iteration = 0; iteration < iterations; ++iteration) {
      parallel_for(
          acting_.size(),
          [&](std::size_t a) {
            const std::uint32_t p = acting_[a];
            const gpu::ContactPair& pair = pairs[p];
            glm::vec4 x[4], v[4];
            for (std::uint32_t i = 0; i < 4u; ++i) {
              x[i] = state_.positions[pair.nodes[i]];
              v[i] = state_.velocities[pair.nodes[i]];
            }
            const std::uint32_t count[4] = {counts_[pair.nodes[0]], counts_[pair.nodes[1]],
                                            counts_[pair.nodes[2]], counts_[pair.nodes[3]]};
            response::solve_contact(pair, x, v, count, k, iteration == 0, impulses_[p],
                                    &corrections_[8u * p]);
          },
          256);
      // The node pass, over the nodes with an active constraint (the others' sums are zero).
      parallel_for(touched_.size(), [&](std::size_t t) {
        const std::uint32_t i = touched_[t];
        glm::vec3 dx(0.0f), dv(0.0f);
        response::gather_correction(active_slots_.data(), active_offset_[i], active_offset_[i + 1],
                                    active_.data(), corrections_.data(), dx, dv);
        response::apply_correction(state_.positions[i], state_.velocities[i], dx, dv);
      });
    }
    // The strays, as GL's last node pass flags them: an untouched node is where the deviation
    // pass measured it.
    parallel_for(nodes, [&](std::size_t i) {
      const glm::vec4& x = state_.positions[i];
      const bool beyond =
          counts_[i] != 0u
              ? response::strayed(x, frame_start_[i], constraints_->node_motion[i], k.elapsed)
              : response::beyond_reach(deviation_[i], x, frame_start_[i]);
      if (beyond) any_strayed.store(true, std::memory_order_relaxed);
    });
  });
  return any_strayed.load();
}

}  // namespace deformcd::cpu
