#pragma once
// The mass-spring step on the GPU: the paper's compute shaders 4 (SpringUpdate), 5 (NodeForce)
// and 3 (NodeUpdate), over SSBOs laid out as in gpu_layout.h, in the CPU backend's layout
// (src/core/sim/node_force_lists.h): each spring edge once, tetrahedron corners node by node.
//
// Thread-to-data mapping, per substep: edge_update.comp runs one invocation per spring edge and
// writes its state (u, q) (SSBO 14); tet_update.comp runs one per stiff tetrahedron and writes
// its corners' volume forces into their slots (SSBO 18); node_update.comp runs one per node,
// sums (k q) u over its springs (SSBOs 15, 16) and its corner slots (SSBO 19), writes the force
// (SSBO 3) and integrates. The gather replaces the scatter-with-atomics a GPU code might use: GL
// 4.3 has no float atomics, and a fixed summation order keeps the result deterministic and equal
// to the CPU's, bit for bit. Against one invocation per spring, the paper's bodies need 4.4x
// fewer spring-state invocations (each edge carries a spring per tetrahedron around it).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/ext/vector_uint4.hpp>
#include <glm/vec4.hpp>

#include "core/sim/frozen_bodies.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/compute_program.h"

namespace deformcd::gl {

struct GlSimulationOptions {
  // Largest buffer upload() accepts, in bytes. 0: the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  // A smaller value caps GPU memory per buffer (and lets tests reach the limit cheaply).
  std::uint64_t max_buffer_bytes = 0;
};

// The buffers of the mass-spring step, bound at the gpu::Binding points. Each holds at least
// one element, so that no binding is ever a zero-size buffer.
struct SimulationBuffers {
  Ssbo<glm::vec4> positions;               // SSBO 0
  Ssbo<glm::vec4> velocities;              // SSBO 1
  Ssbo<gpu::SpringEdge> edges;             // SSBO 2
  Ssbo<glm::vec4> node_forces;             // SSBO 3
  Ssbo<gpu::BodyParams> body_params;       // SSBO 12
  Ssbo<std::uint32_t> node_body;           // SSBO 13
  Ssbo<glm::vec4> edge_states;             // SSBO 14
  Ssbo<std::uint32_t> node_edge_offset;    // SSBO 15
  Ssbo<gpu::EdgeTerm> node_edge_terms;     // SSBO 16
  Ssbo<gpu::Tetra> tets;                   // SSBO 17: the stiff ones
  Ssbo<glm::vec4> corner_forces;           // SSBO 18
  Ssbo<std::uint32_t> node_corner_offset;  // SSBO 19
  Ssbo<glm::uvec4> tet_corner_slots;       // SSBO 20
  std::uint32_t node_count = 0;
  std::uint32_t edge_count = 0;
  std::uint32_t tet_count = 0;   // stiff tetrahedra
  std::uint32_t body_count = 0;  // body_params' length: node_body's values are below it
};

class GlSimulation final : public sim::SimulationBackend {
 public:
  // Makes `context` current and compiles the three shaders (GlError if that fails). The
  // context must outlive this object and be current on the calling thread for every call,
  // destruction included.
  explicit GlSimulation(Context& context, const GlSimulationOptions& options = {});

  [[nodiscard]] std::string_view name() const override { return "gl"; }
  // Renderer, GL version and EGL platform.
  [[nodiscard]] std::string device() const override { return device_; }

  // Checks the state (array sizes agree, each buffer fits the buffer limit, each element count
  // fits one dispatch) before allocating anything, then replaces the buffers. Throws Error for
  // an inconsistent state and GlError naming every buffer that is too large, with its size and
  // the limit; the previous buffers are kept then.
  void upload(const SimulationState& state) override;
  // Binds the buffers (other passes may have rebound the points since), dispatches the edge and
  // tetrahedron passes, a storage barrier, then the node pass, and ends with a barrier so that
  // later shaders and vertex fetches see the new positions. Throws Error before upload().
  void substep(const sim::SubstepConstants& constants) override;
  // glFinish.
  void finish() override;

  void download_positions(std::vector<glm::vec4>& out) override;
  void download_velocities(std::vector<glm::vec4>& out) override;
  void set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) override;
  // The node forces (SSBO 3) of the last substep.
  void download_node_forces(std::vector<glm::vec4>& out);

  // SSBO 0 and 1's buffer names and the node count (all 0 before upload()). An upload()
  // replaces the buffers: a stage that works on them (the contact response) looks them up on
  // each use.
  [[nodiscard]] sim::NodeBuffers node_buffers() override;
  [[nodiscard]] const sim::FrozenBodies& frozen_bodies() const override { return frozen_; }

 private:
  GlSimulation(const DeviceInfo& device, const GlSimulationOptions& options);
  const SimulationBuffers& buffers(const char* operation) const;

  std::string device_;
  std::uint64_t max_buffer_bytes_ = 0;
  bool limit_is_device_ = true;  // whether max_buffer_bytes_ is the device's, for messages
  std::uint32_t max_work_groups_x_ = 0;
  ComputeProgram edge_update_;
  ComputeProgram tet_update_;
  ComputeProgram node_update_;
  std::optional<SimulationBuffers> buffers_;
  // The bodies the shaders skip (sim/frozen_bodies.h), and the body parameters as uploaded
  // (BodyParams::frozen from it): uploaded again when the frozen set changes.
  sim::FrozenBodies frozen_;
  std::vector<gpu::BodyParams> body_params_;
  void upload_frozen();
};

}  // namespace deformcd::gl
