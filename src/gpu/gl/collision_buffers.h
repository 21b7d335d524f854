#pragma once
// The buffers of GlCollision's passes, bound at the gpu::Binding points, and what the host
// knows about them. Node positions (SSBO 0) are not here: they are the simulation's.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "collision_dispatch_plan.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

// Each buffer holds at least one element, so that no binding is ever a zero-size buffer.
struct CollisionBuffers {
  Ssbo<gpu::Box> boxes;                   // SSBO 4: 64 leaf boxes per body
  Ssbo<std::uint32_t> face_flags;         // SSBO 5: per face
  Ssbo<gpu::Face> faces;                  // SSBO 7
  Ssbo<gpu::ObjectInfo> objects;          // SSBO 8
  Ssbo<gpu::BoxFace> box_faces;           // SSBO 9
  Ssbo<gpu::FacePair> face_pairs;         // SSBO 10: pair_capacity slots
  Ssbo<std::int32_t> box_mask;            // SSBO 11: mask slots x 64 x 64
  Ssbo<glm::uvec2> face_boxes;            // SSBO 21
  Ssbo<gpu::BodyPair> body_pairs;         // SSBO 22
  Ssbo<gpu::CollisionCounters> counters;  // SSBO 23: one
  Ssbo<glm::uvec2> box_rows;              // SSBO 24
  std::uint32_t node_count = 0;           // nodes the faces index: SSBO 0 must hold them
  std::uint32_t face_count = 0;
  std::uint32_t box_count = 0;
  std::uint32_t pair_capacity = 0;
  std::vector<PairChunk> octree_chunks;  // rows; at most "mask slots" pairs each
  std::vector<PairChunk> brute_chunks;   // faces; at most the device's z work groups each

  // Binds every buffer at its binding point (other passes may have rebound the points).
  void bind() const {
    boxes.bind(gpu::kBoxInfo);
    face_flags.bind(gpu::kCollisionResult);
    faces.bind(gpu::kFaceInfo);
    objects.bind(gpu::kObjectInfo);
    box_faces.bind(gpu::kBoxFaceList);
    face_pairs.bind(gpu::kFacePair);
    box_mask.bind(gpu::kBoxMask);
    face_boxes.bind(gpu::kFaceBoxes);
    body_pairs.bind(gpu::kBodyPair);
    counters.bind(gpu::kCollisionCounters);
    box_rows.bind(gpu::kBoxRows);
  }
};

}  // namespace deformcd::gl
