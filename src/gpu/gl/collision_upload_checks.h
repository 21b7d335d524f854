#pragma once
// What GlCollision::upload checks before it allocates anything: that a WorldState's collision
// lists fit together, so that no collision shader can index past a buffer, and the sizes of the
// buffers it would create (checked against the limit with check_buffer_sizes). No GL here.

#include <cstdint>
#include <vector>

#include "deformcd/world_state.h"
#include "simulation_upload_checks.h"

namespace deformcd::gl {

// The buffers GlCollision creates for `state`, in binding order: `pair_capacity` face pairs
// (SSBO 10) and `mask_slots` 64 x 64 box masks (SSBO 11).
[[nodiscard]] std::vector<BufferSize> collision_buffer_sizes(const WorldState& state,
                                                             std::uint64_t pair_capacity,
                                                             std::uint64_t mask_slots);

// Throws Error naming the first array or element that does not fit: a face with a node out of
// range, an object whose faces or rows lie outside the arrays or whose leaf boxes are not the
// 64 at 64 x body, a leaf box whose rows lie outside its body's or list another box or a face
// of another body (or one whose face_boxes bit is not set), a body pair that is not a < b <
// bodies.
void check_collision_consistency(const WorldState& state);

}  // namespace deformcd::gl
