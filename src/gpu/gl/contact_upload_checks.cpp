#include "contact_upload_checks.h"

#include <string>

#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

namespace {

[[noreturn]] void misfit(const std::string& what) {
  throw Error("FrameConstraints do not fit the simulation: " + what);
}

void check_pairs(const response::FrameConstraints& c, std::uint32_t node_count) {
  // The pair pass addresses corners as 4 p + k in 32 bits.
  if (c.pairs.size() > 0xFFFFFFFFu / 4u) {
    misfit(std::to_string(c.pairs.size()) + " constraints, more than 32-bit corner slots count");
  }
  for (std::size_t p = 0; p < c.pairs.size(); ++p) {
    const gpu::ContactPair& pair = c.pairs[p];
    if (pair.kind != gpu::kContactVertexFace && pair.kind != gpu::kContactEdgeEdge &&
        pair.kind != gpu::kContactUntangle) {
      misfit("constraint " + std::to_string(p) + " has kind " + std::to_string(pair.kind) +
             ", none of gpu::kContact*");
    }
    for (std::uint32_t n : pair.nodes) {
      if (n >= node_count) {
        misfit("constraint " + std::to_string(p) + " has node " + std::to_string(n) +
               ", but there are " + std::to_string(node_count) + " nodes");
      }
    }
  }
}

void check_node_lists(const response::FrameConstraints& c, std::uint32_t node_count) {
  if (c.node_offset.size() != std::size_t{node_count} + 1u) {
    misfit("node_offset has " + std::to_string(c.node_offset.size()) + " entries for " +
           std::to_string(node_count) + " nodes (needs nodes + 1; index_constraints_by_node)");
  }
  if (c.node_offset.front() != 0u) misfit("node_offset[0] is not 0");
  for (std::size_t i = 0; i + 1 < c.node_offset.size(); ++i) {
    if (c.node_offset[i + 1] < c.node_offset[i]) {
      misfit("node_offset decreases at node " + std::to_string(i));
    }
  }
  if (c.node_list.size() != c.node_offset.back()) {
    misfit("node_list has " + std::to_string(c.node_list.size()) +
           " entries, but node_offset's last entry calls for " +
           std::to_string(c.node_offset.back()));
  }
  const std::size_t corners = 4u * c.pairs.size();
  for (std::size_t e = 0; e < c.node_list.size(); ++e) {
    if (c.node_list[e] >= corners) {
      misfit("node_list[" + std::to_string(e) + "] = " + std::to_string(c.node_list[e]) +
             " names no constraint corner (there are " + std::to_string(corners) + ")");
    }
  }
}

}  // namespace

void check_constraints_fit(const response::FrameConstraints& c, std::uint32_t node_count) {
  check_pairs(c, node_count);
  check_node_lists(c, node_count);
  if (c.node_motion.size() != node_count) {
    misfit("node_motion has " + std::to_string(c.node_motion.size()) + " entries for " +
           std::to_string(node_count) + " nodes");
  }
}

std::vector<BufferSize> contact_buffer_sizes(const response::FrameConstraints& c,
                                             std::uint32_t node_count) {
  const std::uint64_t pairs = c.pairs.size();
  const std::uint64_t nodes = node_count;
  return {
      {"Contact Pair", gpu::kContactPair, pairs, sizeof(gpu::ContactPair)},
      {"Contact Correction", gpu::kContactCorrection, 8u * pairs, sizeof(glm::vec4)},
      {"Node Contact Offset", gpu::kNodeContactOffset, nodes + 1u, sizeof(std::uint32_t)},
      {"Node Contact List", gpu::kNodeContactList, c.node_list.size(), sizeof(std::uint32_t)},
      {"Node Contact Count", gpu::kNodeContactCount, nodes + 1u, sizeof(std::uint32_t)},
      {"Frame Start", gpu::kFrameStart, nodes, sizeof(glm::vec4)},
      {"Node Motion", gpu::kNodeMotion, nodes, sizeof(glm::vec4)},
      {"Node Deviation", gpu::kNodeDeviation, nodes, sizeof(float)},
      {"Contact Impulse", gpu::kContactImpulse, pairs, sizeof(glm::vec4)},
  };
}

}  // namespace deformcd::gl
