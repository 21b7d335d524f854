#pragma once
// The mass-spring step on the CPU, in parallel with oneTBB: the arithmetic of the GL backend's
// shaders (SpringUpdate, TetUpdate, NodeForce, NodeUpdate), with results bit-identical to those
// per-spring passes run on the CPU, computed over an internal layout (sim::SpringEdges,
// sim::TetCorners: each edge once for all its springs, tetrahedron corner forces stored where
// their nodes read them) instead of the state's per-spring arrays. The state's positions and
// velocities are stepped in place.

#include <memory>

#include "core/sim/frozen_bodies.h"
#include "core/sim/node_force_lists.h"
#include "core/sim/simulation_backend.h"
#include "cpu/executor.h"

namespace deformcd::cpu {

class CpuSimulation final : public sim::SimulationBackend {
 public:
  /// Runs its loops on `executor`'s threads.
  explicit CpuSimulation(std::shared_ptr<Executor> executor);
  /// On an executor of its own with `threads` threads (0: every core).
  explicit CpuSimulation(int threads = 0) : CpuSimulation(std::make_shared<Executor>(threads)) {}

  [[nodiscard]] std::string_view name() const override { return "cpu"; }
  [[nodiscard]] std::string device() const override;
  void upload(const SimulationState& state) override;
  void substep(const sim::SubstepConstants& constants) override;
  void finish() override {}
  void download_positions(std::vector<glm::vec4>& out) override { out = state_.positions; }
  void download_velocities(std::vector<glm::vec4>& out) override { out = state_.velocities; }
  void set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) override;
  /// The state's positions and velocities, stepped in place.
  [[nodiscard]] sim::NodeBuffers node_buffers() override;

  /// The state being stepped (for tests; a World's detector reads its positions in place). Its
  /// spring_forces and tet_forces are not written (the step does not go through them).
  [[nodiscard]] const SimulationState& state() const { return state_; }
  [[nodiscard]] const sim::FrozenBodies& frozen_bodies() const override { return frozen_; }

 private:
  void step(const sim::SubstepConstants& constants);
  /// Which batches of edges and of stiff tetrahedra lie in frozen bodies alone (after the
  /// frozen set changed).
  void find_frozen_batches();

  SimulationState state_;
  // Derived from state_ at upload (its springs and tetrahedra do not change afterwards).
  sim::SpringEdges edges_;
  std::vector<glm::vec4> edge_states_;  // per edge: (u, q), sim::spring_edge_state
  sim::TetCorners corners_;
  std::vector<glm::vec4> corner_forces_;  // per corner slot, node-major
  sim::FrozenBodies frozen_;              // bodies the step skips (sim/frozen_bodies.h)
  std::vector<std::uint8_t> edge_batch_frozen_, tet_batch_frozen_;  // per kBatch elements
  std::shared_ptr<Executor> executor_;
};

}  // namespace deformcd::cpu
