#pragma once
// What GlContactResponse::begin_frame checks before it allocates or uploads anything: that a
// frame's constraints fit the simulation they correct, so that no shader reads past a buffer,
// and which buffers they need (for the device's size limit). No GL here: these run, and are
// tested, without a context.

#include <cstdint>
#include <vector>

#include "core/response/frame_constraints.h"
#include "gpu/gl/simulation_upload_checks.h"

namespace deformcd::gl {

// Throws Error naming the first entry that does not fit a simulation of `node_count` nodes: a
// constraint node out of range or an unknown kind, a contact after a volume constraint,
// node_motion not one entry per node, or more corners than 32 bits count. Returns the first
// volume constraint (response::first_volume_constraint): where the solve's second group begins.
std::size_t check_constraints_fit(const response::FrameConstraints& constraints,
                                  std::uint32_t node_count);

// The buffers GlContactResponse needs for `constraints` over `node_count` nodes, in binding
// order, its private work buffers last (for check_buffer_sizes).
[[nodiscard]] std::vector<BufferSize> contact_buffer_sizes(
    const response::FrameConstraints& constraints, std::uint32_t node_count);

}  // namespace deformcd::gl
