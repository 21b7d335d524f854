#pragma once
// The mass-spring step on the CPU, in parallel with oneTBB: the same three phases as the GL
// backend's shaders (SpringUpdate, NodeForce, NodeUpdate), over the same arrays.

#include <memory>

#include "core/sim/simulation_backend.h"
#include "executor.h"

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
  [[nodiscard]] const glm::vec4* host_positions() const override { return state_.positions.data(); }
  [[nodiscard]] SimulationState* host_state() override { return &state_; }

  /// The state being stepped (for tests; a World's detector reads its positions in place).
  [[nodiscard]] const SimulationState& state() const { return state_; }

 private:
  void step(const sim::SubstepConstants& constants);

  SimulationState state_;
  std::shared_ptr<Executor> executor_;
};

}  // namespace deformcd::cpu
