#pragma once
// The contact response on the GPU (issue 12): the same passes as the CPU backend
// (src/cpu/cpu_contact_response.h), as compute shaders over the GL simulation's own node
// buffers, corrected in place between its substeps.
//
// Thread-to-data mapping: response/contact_frame_start.comp runs once per search window, one
// invocation per node, recording its position and its reach (SSBO 34). Each projection then runs
// response/contact_deviation.comp, one invocation per node, writing its projection start (its
// position less h x its velocity, and its distance from its straight path: SSBO 36);
// response/contact_activity.comp, one per constraint, flagging whether it acts (only
// constraints the deviations can have woken look at their geometry);
// response/contact_compact.comp, one work group, listing the acting constraints in order;
// response/contact_count.comp,
// one per node, listing its active slots over its CSR list (SSBOs 31, 32), counting them (SSBO
// 33) and listing the touched nodes; response/contact_dispatch_args.comp, one invocation,
// writing the indirect dispatches from those counts. The host then reads the acting list back
// and colours it (response::SweepOrder, the function the CPU backend calls, so the two sweep in
// the same order) and uploads the sweep's order. Once per iteration, response/contact_sweep.comp,
// one work group, sweeps the colours (the contacts', then the volume constraints'), each
// constraint applying its corrections to its nodes at once, a barrier a colour (no two
// constraints of a colour share a node, so the invocations' order changes no bit); after a last
// iteration's sweep, response/contact_slide.comp, one per touched node, stamps the nodes whose
// contacts slide on. After the iterations asked for, response/contact_residual.comp, one per
// acting constraint, flags one still violated (its flag read back): then one more iteration, to
// kMaxIterationFactor x those asked. Last, response/contact_stray.comp, one per node, flags a
// node beyond its reach. The sweeps touch only the acting constraints and their nodes (on the
// impact scene about 2,200 of 55,000 listed constraints), as the CPU backend's do
// (shaders/response/contact_constraints.glsl mirrors src/core/response/contact_constraints.h).
//
// A frame's constraints are uploaded once, in begin_frame; a projection reads back its acting
// list (for the sweep's colours), one uint at its end (whether a node strayed beyond its reach,
// so that a new search is due), and one more per iteration beyond those asked (whether the
// sweeps have converged).

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec4.hpp>

#include "core/response/response_backend.h"
#include "core/response/sweep_order.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/compute_program.h"

namespace deformcd::gl {

struct GlContactResponseOptions {
  // Largest buffer begin_frame() allocates, in bytes. 0: the device's
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE. A smaller value caps GPU memory per buffer (and lets tests
  // reach the limit cheaply).
  std::uint64_t max_buffer_bytes = 0;
};

// The response's own buffers, bound at the gpu::Binding points. Each is reallocated only when a
// frame needs more than it holds, so a contact set of steady size allocates nothing per frame.
struct ContactBuffers {
  std::optional<Ssbo<gpu::ContactPair>> pairs;      // SSBO 29
  std::optional<Ssbo<std::uint32_t>> slides;        // SSBO 30: per acting constraint
  std::optional<Ssbo<std::uint32_t>> node_offset;   // SSBO 31: nodes + 1
  std::optional<Ssbo<std::uint32_t>> node_list;     // SSBO 32
  std::optional<Ssbo<std::uint32_t>> node_count;    // SSBO 33: two per node
  std::optional<Ssbo<glm::vec4>> frame_start;       // SSBO 34: per node
  std::optional<Ssbo<glm::vec4>> node_motion;       // SSBO 35: per node
  std::optional<Ssbo<glm::vec4>> projection_start;  // SSBO 36: per node
  std::optional<Ssbo<glm::vec4>> impulses;          // SSBO 37: three per acting constraint
  std::optional<Ssbo<std::uint32_t>> node_slid;     // SSBO 38: per node, kept across frames
  std::optional<Ssbo<std::uint32_t>> node_guard;    // SSBO 39: per node, kept across frames
  // The private work buffers (gpu/gl/response_work_buffers.h).
  std::optional<Ssbo<std::uint32_t>> contact_acting;    // 40: per constraint
  std::optional<Ssbo<std::uint32_t>> acting_list;       // 41: per constraint
  std::optional<Ssbo<std::uint32_t>> node_active_slot;  // 42: per node list entry
  std::optional<Ssbo<std::uint32_t>> touched_node;      // 43: per node
  std::optional<Ssbo<std::uint32_t>> state;             // 44: counts, flags, dispatch args
  std::optional<Ssbo<std::uint32_t>> sweep_order;       // 45: per constraint
  std::optional<Ssbo<std::uint32_t>> sweep_colours;     // 46: per colour + 1 (grown as needed)
};

class GlContactResponse final : public response::ResponseBackend {
 public:
  // Corrects the positions and velocities of `simulation` (a simulation in the same context that
  // keeps its nodes in GL buffers: sim::NodeBuffers), which must outlive this. Makes `context`
  // current and compiles the shaders (GlError if that fails). The context must outlive this
  // object and be current on the calling thread for every call, destruction included. The
  // simulation may be uploaded (again) at any time before a begin_frame(); its buffers are
  // looked up on every call.
  GlContactResponse(Context& context, sim::SimulationBackend& simulation,
                    const GlContactResponseOptions& options = {});

  // Checks the constraints against the simulation's nodes and bodies and against the buffer
  // limit before allocating anything (Error for constraints that do not fit, GlError for a
  // buffer too large or a driver that refuses the memory; the previous frame's constraints are
  // kept then), uploads them, and records every node's frame start on the GPU. Throws Error
  // before the simulation's upload().
  void begin_frame(const response::FrameConstraints& constraints) override;
  void update_frame(const response::FrameConstraints& constraints) override;
  // The activity, count, sweep and stray passes with storage barriers between them, ending with a
  // barrier so that the next substep, the collision shaders and renderers see the corrected nodes.
  // Throws Error before begin_frame(), or when the simulation was uploaded again since.
  [[nodiscard]] bool project(const response::ContactConstants& constants, int iterations) override;
  [[nodiscard]] int last_iterations() const override { return iterations_done_; }

  // The frame starts (SSBO 34) that begin_frame recorded, one per node (for tests).
  [[nodiscard]] std::vector<glm::vec4> download_frame_start() const;

 private:
  GlContactResponse(const DeviceInfo& device, sim::SimulationBackend& simulation,
                    const GlContactResponseOptions& options);
  // The simulation's node buffers now; Error naming `caller` unless it keeps them in GL
  // buffers (before its upload, or a simulation of another backend).
  [[nodiscard]] sim::NodeBuffers gl_nodes(const char* caller) const;

  sim::SimulationBackend& simulation_;
  std::uint64_t max_buffer_bytes_ = 0;
  bool limit_is_device_ = true;  // whether max_buffer_bytes_ is the device's, for messages
  std::uint32_t max_work_groups_x_ = 0;
  // Uploads `constraints`, then records the frame starts: the positions now and each node's
  // reach, or (keep_positions, within a window) only the new reaches.
  void upload(const response::FrameConstraints& constraints, bool keep_positions);
  // Error (naming `caller`) before begin_frame(), or when the simulation was uploaded again
  // since.
  void check_frame(const char* caller) const;

  ComputeProgram frame_start_;
  ComputeProgram deviation_;
  ComputeProgram activity_;
  ComputeProgram compact_;
  ComputeProgram count_;
  ComputeProgram dispatch_args_;
  ComputeProgram sweep_;
  ComputeProgram slide_;
  ComputeProgram residual_;
  ComputeProgram stray_;
  int iterations_done_ = 0;    // by the last project()
  std::uint32_t substep_ = 0;  // project() calls so far (the node_slid and node_guard stamps)
  ContactBuffers buffers_;
  // The frame begin_frame set up: project() refuses to run on a simulation uploaded since (its
  // node count or buffers differ), whose frame starts would be stale.
  bool frame_ready_ = false;
  std::uint32_t pair_count_ = 0;
  std::uint32_t first_volume_ =
      0;  // the first volume constraint (response::first_volume_constraint)
  std::uint32_t node_count_ = 0;
  std::uint32_t frame_positions_ = 0;  // the simulation's SSBO 0 name at begin_frame
  const response::FrameConstraints* constraints_ = nullptr;  // the caller's (begin_frame)
  response::SweepOrder sweep_order_;                         // this projection's colours
};

}  // namespace deformcd::gl
