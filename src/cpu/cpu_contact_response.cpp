#include "cpu_contact_response.h"

#include "parallel_for.h"

namespace deformcd::cpu {

CpuContactResponse::CpuContactResponse(SimulationState& state, std::shared_ptr<Executor> executor)
    : state_(state), executor_(std::move(executor)) {}

void CpuContactResponse::begin_frame(const response::FrameConstraints& constraints) {
  constraints_ = constraints;
  const std::size_t nodes = state_.positions.size();
  frame_start_.resize(nodes);
  counts_.assign(nodes, 0u);
  corrections_.assign(8u * constraints_.pairs.size(), glm::vec4(0.0f));
  executor_->run([&] {
    parallel_for(nodes, [&](std::size_t i) {
      frame_start_[i] =
          glm::vec4(glm::vec3(state_.positions[i]), constraints_.body_motion[state_.node_body[i]]);
    });
  });
}

void CpuContactResponse::project(const response::ContactConstants& k) {
  const std::vector<gpu::ContactPair>& pairs = constraints_.pairs;
  executor_->run([&] {
    // Pair pass: each constraint writes its own four slots.
    parallel_for(
        pairs.size(),
        [&](std::size_t p) {
          const gpu::ContactPair& pair = pairs[p];
          glm::vec4 x[4], v[4];
          for (std::uint32_t i = 0; i < 4u; ++i) {
            x[i] = state_.positions[pair.nodes[i]];
            v[i] = state_.velocities[pair.nodes[i]];
          }
          response::solve_contact(pair, x, v, k, &corrections_[8u * p]);
        },
        256);
    const std::uint32_t* offset = constraints_.node_offset.data();
    const std::uint32_t* list = constraints_.node_list.data();
    // Count pass, then node pass: each node reads its own list in order.
    parallel_for(state_.positions.size(), [&](std::size_t i) {
      counts_[i] = response::count_active(list, offset[i], offset[i + 1], corrections_.data());
    });
    parallel_for(state_.positions.size(), [&](std::size_t i) {
      glm::vec3 dx, dv;
      response::gather_correction(list, offset[i], offset[i + 1], corrections_.data(),
                                  pairs.data(), counts_.data(), dx, dv);
      response::apply_correction(state_.positions[i], state_.velocities[i], dx, dv,
                                 frame_start_[i]);
    });
  });
}

}  // namespace deformcd::cpu
