#pragma once
// What GlCollision::upload checks before it allocates anything: that a WorldState's collision
// lists fit together, so that no collision shader can index past a buffer, and the sizes of the
// buffers it would create (checked against the limit with check_buffer_sizes). No GL here.

#include <cstdint>
#include <vector>

#include "deformcd/world_state.h"
#include "simulation_upload_checks.h"

namespace deformcd::gl {

// The sizes of GlCollision's buffers that do not follow from the world.
struct CollisionCapacities {
  std::uint64_t face_pairs = 0;  // FacePair slots (SSBO 10)
  std::uint64_t mask_slots = 0;  // 64 x 64 box masks (SSBO 11)
  std::uint64_t candidates = 0;  // candidate face pairs (SSBO 28)
  std::uint64_t box_pairs = 0;   // octree-compact's box-pair list (private SSBO 30)
};

// The buffers GlCollision creates for `state`, in binding order.
[[nodiscard]] std::vector<BufferSize> collision_buffer_sizes(const WorldState& state,
                                                             const CollisionCapacities& capacities);

// Throws Error naming the first array or element that does not fit: a face with a node out of
// range, an object whose faces or rows lie outside the arrays or whose leaf boxes are not the
// 64 at 64 x body, a leaf box whose rows lie outside its body's or list another box or a face
// of another body (or one whose face_boxes bit is not set), a body pair that is not a <= b <
// bodies, a BVH that is not a tree over its body's faces in preorder right after the previous
// body's (a child before its parent, a parent that does not name it, a face missing or listed
// twice), or deeper than its BodyBvh says or than the traversal stack holds.
void check_collision_consistency(const WorldState& state);

}  // namespace deformcd::gl
