#pragma once
// The count a box-culling broad phase must reach: face pairs of the world's body pairs (of
// different bodies) whose exact bounding boxes overlap, by testing every such pair.

#include <cstdint>

#include <glm/vec3.hpp>

#include "core/collision/broad_phase.h"
#include "deformcd/world_state.h"

namespace deformcd::test {

/// The bounding box of face `face` at the world's positions.
inline gpu::Box face_box(const WorldState& w, std::uint32_t face) {
  gpu::Box b = collision::empty_box();
  for (std::uint32_t n : {w.faces[face].a, w.faces[face].b, w.faces[face].c})
    collision::grow_box(b, glm::vec3(w.positions[n]));
  return b;
}

/// Face pairs of w.body_pairs whose boxes overlap: what the bvh broad phase hands on.
inline std::uint64_t face_box_overlaps(const WorldState& w) {
  std::uint64_t count = 0;
  for (const gpu::BodyPair& pair : w.body_pairs) {
    const gpu::ObjectInfo& a = w.objects[pair.a];
    const gpu::ObjectInfo& b = w.objects[pair.b];
    for (std::uint32_t fa = a.face_offset; fa < a.face_offset + a.face_count; ++fa) {
      for (std::uint32_t fb = b.face_offset; fb < b.face_offset + b.face_count; ++fb)
        count += collision::boxes_overlap(face_box(w, fa), face_box(w, fb)) ? 1u : 0u;
    }
  }
  return count;
}

}  // namespace deformcd::test
