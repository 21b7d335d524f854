#pragma once
// Pre-processing of the paper's octree (its Fig. 7): which surface faces each of a body's 64 leaf
// boxes holds. The boxes' extents are not fixed here: each frame they are recomputed from their
// faces' current vertices (BBUpdate), so they follow the deformation.
//
// The rule: over the body's rest pose (its surface's bounding box), a 3-level octree splits
// each axis in 4, giving 64 leaf cells numbered in octree (Morton) order, index = 8 x (level-2
// octant) + (level-3 octant), an octant being x + 2 y + 4 z of the cell's bit at that level.
// A face is listed under every leaf cell that its rest-pose bounding box overlaps (half-open
// cells, the last one closed), so a face straddling cells is listed under each of them and N'
// (rows) >= N (faces). Any rule listing each face at least once gives the same contacts; this
// one keeps boxes tight around their faces.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Octree (Morton) index of leaf cell (x, y, z), each coordinate in 0..3.
[[nodiscard]] constexpr std::uint32_t leaf_index(std::uint32_t x, std::uint32_t y,
                                                 std::uint32_t z) {
  const std::uint32_t level2 = (x >> 1u) | ((y >> 1u) << 1u) | ((z >> 1u) << 2u);
  const std::uint32_t level3 = (x & 1u) | ((y & 1u) << 1u) | ((z & 1u) << 2u);
  return 8u * level2 + level3;
}

/// One body's BoundingBox Face List.
struct LeafBoxLists {
  std::vector<gpu::BoxFace> rows;      ///< box by box, faces in increasing order within a box
  std::vector<glm::uvec2> face_boxes;  ///< per face of the body: bit k (x: 0-31, y: 32-63)
};

/// Lists the faces (global indices face_offset + i, vertices at `positions`) under the leaf
/// cells of their rest-pose bounding boxes.
[[nodiscard]] LeafBoxLists build_leaf_box_lists(VertexPositions positions, const gpu::Face* faces,
                                                std::uint32_t face_count,
                                                std::uint32_t face_offset);

}  // namespace deformcd::collision
