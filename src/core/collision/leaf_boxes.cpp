#include "collision/leaf_boxes.h"

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

LeafBoxLists build_leaf_box_lists(const std::vector<glm::vec4>& positions, const gpu::Face* faces,
                                  std::uint32_t face_count, std::uint32_t face_offset) {
  glm::dvec3 lo(std::numeric_limits<double>::max());
  glm::dvec3 hi(std::numeric_limits<double>::lowest());
  for (std::uint32_t f = 0; f < face_count; ++f) {
    for (std::uint32_t node : {faces[f].a, faces[f].b, faces[f].c}) {
      lo = glm::min(lo, glm::dvec3(positions[node]));
      hi = glm::max(hi, glm::dvec3(positions[node]));
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
      face_lo = glm::min(face_lo, glm::dvec3(positions[node]));
      face_hi = glm::max(face_hi, glm::dvec3(positions[node]));
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

void assemble_collision_lists(WorldState& state, bool self_collision) {
  state.box_faces.clear();
  state.face_boxes.clear();
  state.body_pairs.clear();
  state.box_rows.clear();
  for (std::size_t b = 0; b < state.objects.size(); ++b) {
    gpu::ObjectInfo& o = state.objects[b];
    const LeafBoxLists lists = build_leaf_box_lists(
        state.positions, state.faces.data() + o.face_offset, o.face_count, o.face_offset);
    o.box_offset = static_cast<std::uint32_t>(b) * gpu::kLeafBoxesPerBody;
    o.box_count = gpu::kLeafBoxesPerBody;
    o.box_face_offset = static_cast<std::uint32_t>(state.box_faces.size());
    o.box_face_count = static_cast<std::uint32_t>(lists.rows.size());
    std::uint32_t row = o.box_face_offset;
    for (std::uint32_t box = 0; box < gpu::kLeafBoxesPerBody; ++box) {
      std::uint32_t count = 0;
      while (row + count - o.box_face_offset < lists.rows.size() &&
             lists.rows[row + count - o.box_face_offset].box == box)
        ++count;
      state.box_rows.emplace_back(row, count);
      row += count;
    }
    state.box_faces.insert(state.box_faces.end(), lists.rows.begin(), lists.rows.end());
    state.face_boxes.insert(state.face_boxes.end(), lists.face_boxes.begin(),
                            lists.face_boxes.end());
  }
  const auto bodies = static_cast<std::uint32_t>(state.objects.size());
  for (std::uint32_t a = 0; a < bodies; ++a) {
    for (std::uint32_t b = self_collision ? a : a + 1; b < bodies; ++b)
      state.body_pairs.push_back({a, b});
  }
}

}  // namespace deformcd::collision
