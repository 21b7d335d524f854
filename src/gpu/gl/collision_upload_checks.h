#pragma once
// What GlCollision::upload checks before it allocates anything: that the collision data fits
// together, so that no collision shader can index past a buffer, and the sizes of the buffers
// it would create (checked against the limit with check_buffer_sizes). No GL here.

#include <cstdint>
#include <vector>

#include "core/collision/collision_data.h"
#include "gpu/gl/simulation_upload_checks.h"

namespace deformcd::gl {

// The sizes of GlCollision's buffers that do not follow from the collision data.
struct CollisionCapacities {
  std::uint64_t face_pairs = 0;  // FacePair slots (SSBO 10)
  std::uint64_t mask_slots = 0;  // 64 x 64 box masks (SSBO 11)
  std::uint64_t candidates = 0;  // candidate face pairs (SSBO 28)
  std::uint64_t box_pairs = 0;   // octree-compact's box-pair list (private SSBO 30)
};

// The buffers GlCollision creates for `data` (hierarchies built), in binding order.
[[nodiscard]] std::vector<BufferSize> collision_buffer_sizes(const collision::CollisionData& data,
                                                             const CollisionCapacities& capacities);

// Throws Error naming the first array or element that does not fit: a face of a mesh that does
// not exist, outside its mesh's face range, or with a vertex out of the mesh's range; a mesh
// whose faces or leaf-box rows reach past the arrays; a mesh pair not a <= b < meshes; no
// hierarchies; face_boxes or box_rows of the wrong length, a leaf box whose rows lie outside
// its mesh's or name another box, a face of another mesh or a face whose face_boxes lacks the
// box; a BVH that is not a tree over its mesh's faces in preorder right
// after the previous mesh's (a child before its parent, a parent that does not name it, a face
// missing or listed twice), or deeper than its BodyBvh says or than the traversal stack holds.
void check_collision_data(const collision::CollisionData& data);

}  // namespace deformcd::gl
