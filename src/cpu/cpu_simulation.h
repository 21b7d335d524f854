#pragma once
// The mass-spring step on the CPU, in parallel with oneTBB: the same three phases as the GL
// backend's shaders (SpringUpdate, NodeForce, NodeUpdate), over the same arrays.

#include <tbb/global_control.h>
#include <memory>

#include "core/sim/simulation_backend.h"

namespace deformcd::cpu {

class CpuSimulation final : public sim::SimulationBackend {
 public:
  /// `threads` = 0 uses every core; otherwise at most that many threads.
  explicit CpuSimulation(int threads = 0);

  [[nodiscard]] std::string_view name() const override { return "cpu"; }
  [[nodiscard]] std::string device() const override;
  void upload(const WorldState& state) override;
  void substep(const sim::SubstepConstants& constants) override;
  void finish() override {}
  void download_positions(std::vector<glm::vec4>& out) override { out = state_.positions; }
  void download_velocities(std::vector<glm::vec4>& out) override { out = state_.velocities; }

  /// The state being stepped (for tests and for the CPU collision pipeline).
  [[nodiscard]] const WorldState& state() const { return state_; }

 private:
  WorldState state_;
  int threads_;
  std::unique_ptr<tbb::global_control> limit_;
};

}  // namespace deformcd::cpu
