#pragma once
// The contact constraints of one frame (issue 12), as both response backends take them: the
// constraints, and per node the CSR list of its constraint corners, so that each node gathers
// its corrections in a fixed order (GL 4.3 has no float atomics, and the sum must not depend on
// the schedule).

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::response {

struct FrameConstraints {
  std::vector<gpu::ContactPair> pairs;  ///< SSBO 29, in the proximity search's order
  /// SSBO 31: node n's corners are node_list[node_offset[n] .. node_offset[n + 1]).
  std::vector<std::uint32_t> node_offset;
  /// SSBO 32: slots 4 p + k (pair p's node k), ascending within each node.
  std::vector<std::uint32_t> node_list;
  /// SSBO 35, per node: the velocity of its straight path over the search window (xyz, m/s:
  /// its velocity where the window starts) and its reach (w, m; infinite for a node on no
  /// collision surface): a free node stays within the reach of its window-start position
  /// carried along that path; the proximity search assumed no more.
  std::vector<glm::vec4> node_motion;
};

/// Fills node_offset and node_list for `node_count` nodes from `pairs` (count, scan, emit in
/// slot order, so each node's list is ascending).
void index_constraints_by_node(std::uint32_t node_count, FrameConstraints& constraints);

}  // namespace deformcd::response
