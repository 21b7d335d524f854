#pragma once
// What GlSimulation::upload checks before it allocates anything: that a SimulationState's arrays
// fit together, so that no shader can index past a buffer, and that every buffer fits the device
// (check_buffer_sizes serves GlCollision::upload too). No GL here: these run, and are tested,
// without a context.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "core/sim/node_force_lists.h"
#include "deformcd/simulation_state.h"

namespace deformcd::gl {

// One buffer the simulation would create.
struct BufferSize {
  std::string_view name;  // the paper's Table 1 name, or ours beyond it
  std::uint32_t binding;  // gpu::Binding
  std::uint64_t count;    // elements
  std::uint64_t element_bytes;

  [[nodiscard]] std::uint64_t bytes() const { return count * element_bytes; }
};

// The buffers GlSimulation creates for `state`, whose spring edges and tetrahedron corners are
// `edges` and `corners` (sim::build_spring_edges, sim::build_tet_corners), in binding order.
[[nodiscard]] std::vector<BufferSize> simulation_buffer_sizes(const SimulationState& state,
                                                              const sim::SpringEdges& edges,
                                                              const sim::TetCorners& corners);

// Throws GlError when any buffer holds more than `max_bytes`, naming each such buffer with its
// size and the limit; `limit_name` says whose limit it is, `owner` whose buffers they are (the
// message's first words).
void check_buffer_sizes(std::span<const BufferSize> buffers, std::uint64_t max_bytes,
                        std::string_view limit_name, std::string_view owner = "GL simulation");

// Throws Error naming the first array or element that does not fit: a per-node array whose
// length differs from positions', a per-spring one from springs', a node, body or spring index
// out of range, CSR offsets that are not a non-decreasing cover of the spring list.
void check_world_consistency(const SimulationState& state);

}  // namespace deformcd::gl
