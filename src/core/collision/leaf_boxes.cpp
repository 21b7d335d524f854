#include "core/collision/leaf_boxes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace deformcd::collision {

namespace {

// The leaf cell (0..3) along one axis holding coordinate v of a body spanning [lo, lo + extent].
std::uint32_t cell_of(double v, double lo, double extent) {
  if (!(extent > 0.0)) return 0;  // a flat body: one layer of cells
  const double cell = std::floor(4.0 * (v - lo) / extent);
  return static_cast<std::uint32_t>(std::clamp(cell, 0.0, 3.0));
}

}  // namespace

LeafBoxLists build_leaf_box_lists(VertexPositions positions, const gpu::Face* faces,
                                  std::uint32_t face_count, std::uint32_t face_offset) {
  glm::dvec3 lo(std::numeric_limits<double>::max());
  glm::dvec3 hi(std::numeric_limits<double>::lowest());
  for (std::uint32_t f = 0; f < face_count; ++f) {
    for (std::uint32_t node : {faces[f].a, faces[f].b, faces[f].c}) {
      const glm::dvec3 p(vertex_position(positions, faces[f].body, node));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  const glm::dvec3 extent = hi - lo;

  LeafBoxLists lists;
  lists.face_boxes.assign(face_count, glm::uvec2(0u));
  std::vector<std::vector<std::uint32_t>> faces_of_box(gpu::kLeafBoxesPerBody);
  for (std::uint32_t f = 0; f < face_count; ++f) {
    glm::dvec3 face_lo(std::numeric_limits<double>::max());
    glm::dvec3 face_hi(std::numeric_limits<double>::lowest());
    for (std::uint32_t node : {faces[f].a, faces[f].b, faces[f].c}) {
      const glm::dvec3 p(vertex_position(positions, faces[f].body, node));
      face_lo = glm::min(face_lo, p);
      face_hi = glm::max(face_hi, p);
    }
    std::uint32_t first[3];
    std::uint32_t last[3];
    for (int c = 0; c < 3; ++c) {
      first[c] = cell_of(face_lo[c], lo[c], extent[c]);
      last[c] = cell_of(face_hi[c], lo[c], extent[c]);
    }
    for (std::uint32_t z = first[2]; z <= last[2]; ++z) {
      for (std::uint32_t y = first[1]; y <= last[1]; ++y) {
        for (std::uint32_t x = first[0]; x <= last[0]; ++x) {
          const std::uint32_t box = leaf_index(x, y, z);
          faces_of_box[box].push_back(f);
          lists.face_boxes[f][box / 32u] |= 1u << (box % 32u);
        }
      }
    }
  }
  for (std::uint32_t box = 0; box < gpu::kLeafBoxesPerBody; ++box) {
    for (std::uint32_t f : faces_of_box[box])
      lists.rows.push_back({face_offset + f, box});
  }
  return lists;
}

}  // namespace deformcd::collision
