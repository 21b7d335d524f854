#pragma once
// The line between the world and a backend is drawn at the level of a simulation phase: the
// world hands the backend its state once, asks for substeps, and reads results back. The CPU
// backend (src/cpu) and the GL backend (src/gpu/gl) implement it.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

#include "core/sim/mass_spring.h"
#include "deformcd/simulation_state.h"

namespace deformcd::sim {

/// Throws Error unless nodes [first, first + count) lie within a state of `node_count` nodes.
void check_node_range(std::uint32_t first, std::size_t count, std::size_t node_count);

class SimulationBackend {
 public:
  virtual ~SimulationBackend() = default;
  SimulationBackend(const SimulationBackend&) = delete;
  SimulationBackend& operator=(const SimulationBackend&) = delete;

  /// "cpu" or "gl".
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// What runs it: thread count, or the GL renderer and version.
  [[nodiscard]] virtual std::string device() const = 0;

  /// Takes the world's initial state (sizes are fixed from then on). Throws Error when it
  /// does not fit (e.g. a buffer larger than the device allows).
  virtual void upload(const SimulationState& state) = 0;
  /// One substep: spring forces, node forces, integration.
  virtual void substep(const SubstepConstants& constants) = 0;
  /// Waits for the work issued so far (for timing).
  virtual void finish() = 0;

  virtual void download_positions(std::vector<glm::vec4>& out) = 0;
  virtual void download_velocities(std::vector<glm::vec4>& out) = 0;
  /// Gives nodes [first, first + inverse_mass.size()) those inverse masses (0 holds a node
  /// still: it keeps velocity 0 and is an immovable obstacle to the contact response) and
  /// zeroes their velocities; their positions stay. A sleeping body's nodes are held so, and
  /// given their masses back when it wakes. Throws Error when the range is outside the state.
  virtual void set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) = 0;

  /// GL buffer name of the node positions, or 0 when the backend is not GL.
  [[nodiscard]] virtual std::uint32_t gl_position_buffer() const { return 0; }
  /// The node positions in host memory (vec4 per node), where a CPU backend steps them in
  /// place (they do not move after upload), or null when the backend is not the CPU.
  [[nodiscard]] virtual const glm::vec4* host_positions() const { return nullptr; }
  /// GL buffer name of the node velocities, or 0 when the backend is not GL.
  [[nodiscard]] virtual std::uint32_t gl_velocity_buffer() const { return 0; }
  /// The state a CPU backend steps, whose positions and velocities (vec4 per node, in node
  /// order) stay valid between substeps, so that a contact response can correct them in
  /// place; null when the backend is not the CPU.
  [[nodiscard]] virtual SimulationState* host_state() { return nullptr; }

 protected:
  SimulationBackend() = default;
};

}  // namespace deformcd::sim
