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

#include "core/sim/frozen_bodies.h"
#include "core/sim/mass_spring.h"
#include "deformcd/simulation_state.h"

namespace deformcd::sim {

/// Where a simulation keeps its nodes' positions and velocities (glm::vec4 per node, in node
/// order; a position's w is the node's inverse mass), for the stages that read them in place (a
/// detector, a renderer) or correct them between substeps (a contact response): arrays in host
/// memory (the CPU backend; they stay where they are after upload) or GL buffers (the GL
/// backend; an upload replaces them: ask again after one). All empty before upload.
struct NodeBuffers {
  std::uint32_t node_count = 0;
  glm::vec4* host_positions = nullptr;   ///< the CPU backend's, else null
  glm::vec4* host_velocities = nullptr;  ///< the CPU backend's, else null
  std::uint32_t gl_positions = 0;        ///< GL buffer name (the GL backend's), else 0
  std::uint32_t gl_velocities = 0;       ///< GL buffer name (the GL backend's), else 0
};

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
  /// Which bodies can move (FrozenBodies::can_move) and which the substeps skip.
  [[nodiscard]] virtual const FrozenBodies& frozen_bodies() const = 0;

  /// The nodes' positions and velocities where this backend keeps them (NodeBuffers).
  [[nodiscard]] virtual NodeBuffers node_buffers() = 0;

 protected:
  SimulationBackend() = default;
};

}  // namespace deformcd::sim
