#pragma once
// The contact response on the CPU, in parallel with oneTBB: the same passes as the GL backend's
// shaders (deviation, activity, compaction, count, sweeps, stray) over a simulation's positions
// and velocities in place (in host memory: sim::NodeBuffers), with the same results. Only the
// active constraints (a few percent of the window's candidates) are counted and solved: their
// list is compacted after the activity pass in constraint order, the contacts' counts summed
// from it, and each iteration sweeps them in the colours' order (response::SweepOrder: the
// contacts, then the volume constraints; each group's two halves, which share no node, on two
// threads, the constraints across them on one; the passes around the sweeps run in parallel),
// each applying its corrections to its nodes at once. The stray check after the
// iterations watches the reaches.

#include <array>
#include <memory>
#include <vector>

#include "core/response/response_backend.h"
#include "core/response/sweep_order.h"
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
  // Per acting constraint, in the sweep's order (swept_pairs_): three of what it gave this
  // substep (impulses_), and the corners whose contact slides in the last sweep (slides_: bit k
  // for corner k).
  std::vector<glm::vec4> impulses_;
  std::vector<std::uint8_t> slides_;
  response::SweepOrder sweep_;  // the acting constraints' colours, this substep
  // A sweep's work: swept_[begin, end); it may start once the sweep's first `stage` items are
  // done.
  struct SweepItem {
    std::uint32_t begin, end, stage;
  };
  std::vector<SweepItem> items_;      // one sweep's, in order
  std::vector<std::uint32_t> swept_;  // acting places, item by item (each half's colours)
  // Per node n: its active contacts (2 n) and volume constraints (2 n + 1) this substep (the
  // contacts' mass splitting; a node with either is touched).
  std::vector<std::uint32_t> counts_;
  std::size_t first_volume_ = 0;               // the first volume constraint (all after it are)
  std::vector<std::uint32_t> active_;          // per constraint: 1 when it acts this substep
  std::vector<std::uint32_t> acting_;          // the active constraints, ascending
  std::vector<std::uint32_t> block_starts_;    // scratch of the acting list (parallel_select)
  std::vector<gpu::ContactPair> swept_pairs_;  // their copies, in the sweep's order
  std::vector<std::array<std::uint32_t, 4>> swept_slots_;  // their nodes' slots in local_
  std::vector<std::uint32_t> slot_;  // per node: its slot in local_ (touched nodes only)
  /// A touched node's position and velocity as the sweeps correct them: one cache line holds
  /// both (a constraint's node costs one line, not two).
  struct alignas(32) LocalNode {
    glm::vec4 x;
    glm::vec4 v;
  };
  std::vector<LocalNode> local_;
  std::vector<std::uint32_t> touched_;  // the nodes of active constraints, as first named
  std::uint32_t substep_ = 0;           // project() calls so far
  std::vector<std::uint32_t> guard_;    // per node: the last projection a guarding contact named it
  std::vector<std::uint32_t> slid_;     // per node: the last substep a contact of it slid in
  std::vector<std::uint32_t> watched_;  // the nodes with a finite reach, ascending
  std::vector<glm::vec4> start_;        // per node: response::projection_start, this substep
};

}  // namespace deformcd::cpu
