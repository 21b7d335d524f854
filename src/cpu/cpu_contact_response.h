#pragma once
// The contact response on the CPU, in parallel with oneTBB: the same passes as the GL backend's
// shaders (deviation, activity, compaction, count, solve, node, stray) over a simulation's
// positions and velocities in place (in host memory: sim::NodeBuffers), with the same results.
// Only the active constraints (a few percent of the window's candidates) are counted and solved:
// their list is compacted after the activity pass in constraint order, the counts summed from
// it, and each node's active slots listed in its list's order, so the node pass adds GL's terms
// in GL's order without walking the inactive slots. The node passes visit only the nodes the
// active constraints touch: every other node's corrections are zero, and the stray check after
// the iterations watches the reaches. Each projection solves the contacts, then the volume
// constraints (response::first_volume_constraint), each group with its own counts and node pass.

#include <memory>
#include <vector>

#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "cpu/executor.h"

namespace deformcd::cpu {

class CpuContactResponse final : public response::ResponseBackend {
 public:
  /// Corrects the nodes of `simulation` (which must outlive this and keep them in host memory:
  /// its node_buffers(), looked up at each begin_frame()) on `executor`'s threads.
  CpuContactResponse(sim::SimulationBackend& simulation, std::shared_ptr<Executor> executor);

  void begin_frame(const response::FrameConstraints& constraints) override;
  void update_frame(const response::FrameConstraints& constraints) override;
  [[nodiscard]] bool project(const response::ContactConstants& constants, int iterations) override;
  [[nodiscard]] int last_iterations() const override { return iterations_done_; }

 private:
  // Points at `constraints` (the caller keeps them) and sizes the per-constraint arrays.
  void take(const response::FrameConstraints& constraints);
  // Lists the nodes with a finite reach (watched_) from frame_start_.
  void watch_reachable_nodes();
  // Where `pair`'s nodes started the window (frame_start_), for the constraint functions' window
  // start: loaded only where contact_geometry reads it (response::reads_window_start), else 0.
  void load_window_start(const gpu::ContactPair& pair, glm::vec3 window_start[4]) const;

  sim::SimulationBackend& simulation_;
  int iterations_done_ = 0;  // by the last project()
  sim::NodeBuffers nodes_;   // the simulation's, as begin_frame() found them
  std::shared_ptr<Executor> executor_;
  const response::FrameConstraints* constraints_ = nullptr;  // the caller's (begin_frame)
  std::vector<glm::vec4> frame_start_;  // per node: position at the frame's start, w = reach
  // Per acting constraint acting_[a]: two per corner (slot 4 a + k), position and velocity
  // change; three of what it gave this substep.
  std::vector<glm::vec4> corrections_;
  std::vector<glm::vec4> impulses_;
  // Per node n: its active contacts (2 n) and volume constraints (2 n + 1) this substep.
  std::vector<std::uint32_t> counts_;
  std::size_t first_volume_ = 0;                // the first volume constraint (all after it are)
  std::vector<std::uint32_t> active_;           // per constraint: 1 when it acts this substep
  std::vector<std::uint32_t> acting_;           // the active constraints, ascending
  std::vector<gpu::ContactPair> acting_pairs_;  // their copies, in that order
  std::vector<std::uint32_t> touched_;          // the nodes of active constraints, as first named
  std::uint32_t substep_ = 0;                   // project() calls so far
  std::vector<std::uint32_t> guard_;    // per node: the last projection a guarding contact named it
  std::vector<std::uint32_t> slid_;     // per node: the last substep a contact of it slid in
  std::vector<std::uint32_t> watched_;  // the nodes with a finite reach, ascending
  std::vector<glm::vec4> start_;        // per node: response::projection_start, this substep
  // Per touched node n, its active slots: active_slots_[slot_begin_[n] ..), the contacts'
  // (counts_[2 n]) then the volume constraints' (counts_[2 n + 1]).
  std::vector<std::uint32_t> slot_begin_;
  std::vector<std::uint32_t> active_slots_;
  std::vector<std::uint32_t> slot_cursor_;  // the fill's per node position
};

}  // namespace deformcd::cpu
