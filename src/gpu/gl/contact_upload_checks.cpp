#include "gpu/gl/contact_upload_checks.h"

#include <string>

#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/response_work_buffers.h"

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
        pair.kind != gpu::kContactUntangle && pair.kind != gpu::kContactVolume) {
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

}  // namespace

std::size_t check_constraints_fit(const response::FrameConstraints& c, std::uint32_t node_count) {
  check_pairs(c, node_count);
  const std::size_t first_volume = response::first_volume_constraint(c.pairs);
  if (c.node_motion.size() != node_count) {
    misfit("node_motion has " + std::to_string(c.node_motion.size()) + " entries for " +
           std::to_string(node_count) + " nodes");
  }
  if (c.window_start.size() != node_count) {
    misfit("window_start has " + std::to_string(c.window_start.size()) + " entries for " +
           std::to_string(node_count) + " nodes");
  }
  return first_volume;
}

std::vector<BufferSize> contact_buffer_sizes(const response::FrameConstraints& c,
                                             std::uint32_t node_count) {
  const std::uint64_t pairs = c.pairs.size();
  const std::uint64_t nodes = node_count;
  return {
      {"Contact Pair", gpu::kContactPair, pairs, sizeof(gpu::ContactPair)},
      // At most every constraint acts in a projection.
      {"Contact Slides", gpu::kContactSlides, pairs, sizeof(std::uint32_t)},
      {"Node Contact Offset", gpu::kNodeContactOffset, nodes + 1u, sizeof(std::uint32_t)},
      {"Node Contact List", gpu::kNodeContactList, 4u * pairs, sizeof(std::uint32_t)},
      {"Node Contact Count", gpu::kNodeContactCount, 2u * nodes, sizeof(std::uint32_t)},
      {"Frame Start", gpu::kFrameStart, nodes, sizeof(glm::vec4)},
      {"Node Motion", gpu::kNodeMotion, nodes, sizeof(glm::vec4)},
      {"Projection Start", gpu::kProjectionStart, nodes, sizeof(glm::vec4)},
      {"Contact Impulse", gpu::kContactImpulse, 3u * pairs, sizeof(glm::vec4)},
      {"Node Slid", gpu::kNodeSlid, nodes, sizeof(std::uint32_t)},
      {"Node Guard", gpu::kNodeGuard, nodes, sizeof(std::uint32_t)},
      {"Contact Acting", kContactActingBinding, pairs, sizeof(std::uint32_t)},
      {"Acting List", kActingListBinding, pairs, sizeof(std::uint32_t)},
      {"Node Active Slot", kNodeActiveSlotBinding, 4u * pairs, sizeof(std::uint32_t)},
      {"Touched Node", kTouchedNodeBinding, nodes, sizeof(std::uint32_t)},
      {"Response State", kResponseStateBinding, kResponseStateWords, sizeof(std::uint32_t)},
      {"Sweep Order", kSweepOrderBinding, pairs, sizeof(std::uint32_t)},
      // At most a colour per acting constraint.
      {"Sweep Colours", kSweepColoursBinding, pairs + 1u, sizeof(std::uint32_t)},
  };
}

}  // namespace deformcd::gl
