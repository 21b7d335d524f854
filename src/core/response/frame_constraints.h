#pragma once
// The contact constraints of one search window (issue 12), as both response backends take
// them, and the per-node lists of their corners the GL backend gathers each node's corrections
// through in a fixed order (GL 4.3 has no float atomics, and the sum must not depend on the
// schedule; the CPU backend lists only the active constraints' corners, every substep).

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::response {

struct FrameConstraints {
  std::vector<gpu::ContactPair> pairs;  ///< in the proximity search's order
  /// Per node: the velocity of its straight path over the search window (xyz, m/s:
  /// its velocity where the window starts) and its reach (w, m; infinite for a node on no
  /// collision surface): a free node stays within the reach of its window-start position
  /// carried along that path; the proximity search assumed no more.
  std::vector<glm::vec4> node_motion;
  /// Per node: its position where the window starts (the host's copy, which the backends'
  /// sweeps split in halves by: response::SweepOrder).
  std::vector<glm::vec3> window_start;
};

/// The index of `pairs`' first volume constraint (gpu::kContactVolume), pairs.size() when
/// there is none. Throws Error when another kind follows one: the backends solve the volume
/// constraints after the contacts, as the last group of the list.
[[nodiscard]] std::size_t first_volume_constraint(const std::vector<gpu::ContactPair>& pairs);

/// Per node, the corners of the constraints it is in.
struct NodeContactLists {
  /// Node n's corners are list[offset[n] .. offset[n + 1]).
  std::vector<std::uint32_t> offset;
  /// Slots 4 p + k (pair p's node k), ascending within each node.
  std::vector<std::uint32_t> list;
};

/// The lists of `node_count` nodes for `pairs`, whose nodes are below node_count (count, scan,
/// emit in slot order, so each node's list is ascending).
[[nodiscard]] NodeContactLists index_constraints_by_node(
    std::uint32_t node_count, const std::vector<gpu::ContactPair>& pairs);

}  // namespace deformcd::response
