#pragma once
// The buffers of GlCollision's passes, bound at the gpu::Binding points (the private work
// buffers at collision_work_buffers.h's), and what the host knows about them. Vertex positions
// (SSBO 0) are not here: they are the caller's, or gathered by PositionStaging.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/collision_dispatch_plan.h"
#include "gpu/gl/collision_work_buffers.h"

namespace deformcd::gl {

// Each buffer holds at least one element, so that no binding is ever a zero-size buffer.
struct CollisionBuffers {
  Ssbo<gpu::Box> boxes;                   // SSBO 4: 64 leaf boxes per mesh
  Ssbo<std::uint32_t> face_flags;         // SSBO 5: per face
  Ssbo<gpu::Face> faces;                  // SSBO 7
  Ssbo<gpu::MeshInfo> meshes;             // SSBO 8: position_* set by PositionStaging
  Ssbo<gpu::BoxFace> box_faces;           // SSBO 9
  Ssbo<gpu::FacePair> face_pairs;         // SSBO 10: pair_capacity slots
  Ssbo<std::int32_t> box_mask;            // SSBO 11: mask slots x 64 x 64
  Ssbo<glm::uvec2> face_boxes;            // SSBO 21
  Ssbo<gpu::BodyPair> mesh_pairs;         // SSBO 22
  Ssbo<gpu::CollisionCounters> counters;  // SSBO 23: one
  Ssbo<glm::uvec2> box_rows;              // SSBO 24
  Ssbo<gpu::BvhNode> bvh_nodes;           // SSBO 25
  Ssbo<gpu::Box> bvh_boxes;               // SSBO 26: per BVH node
  Ssbo<gpu::BodyBvh> mesh_bvhs;           // SSBO 27
  Ssbo<glm::uvec2> candidates;            // SSBO 28: candidate_capacity slots
  Ssbo<std::uint32_t> dispatch_args;      // 29: also the GL_DISPATCH_INDIRECT_BUFFER
  Ssbo<glm::uvec2> box_pair_list;         // 30: box_pair_capacity slots
  Ssbo<std::uint32_t> bvh_levels;         // 31: internal BVH nodes, deepest level first
  Ssbo<gpu::BodyPair> touching_pairs;     // 32: room for every mesh pair
  Ssbo<std::uint32_t> bvh_leaves;         // 33: per face, leaves in preorder
  std::uint32_t face_count = 0;
  std::uint32_t box_count = 0;
  std::uint32_t pair_capacity = 0;
  std::uint32_t bvh_node_count = 0;
  std::vector<glm::uvec2> bvh_levels_ranges;  // (first, count) in bvh_levels, deepest first
  std::uint32_t candidate_capacity = 0;
  std::uint32_t box_pair_capacity = 0;
  std::uint32_t max_box_rows = 0;  // largest row count of any leaf box
  std::uint32_t mesh_pair_count = 0;
  // Largest face count of the smaller mesh of a mesh pair: bvh_traverse.comp's x extent.
  std::uint32_t max_query_faces = 0;
  std::vector<PairChunk> octree_chunks;  // rows; at most "mask slots" pairs each
  // Faces; at most the device's z work groups each (also octree-compact's box-pair list's).
  std::vector<PairChunk> brute_chunks;

  // Binds every buffer at its binding point (other passes may have rebound the points).
  void bind() const {
    boxes.bind(gpu::kBoxInfo);
    face_flags.bind(gpu::kCollisionResult);
    faces.bind(gpu::kFaceInfo);
    meshes.bind(gpu::kMeshInfo);
    box_faces.bind(gpu::kBoxFaceList);
    face_pairs.bind(gpu::kFacePair);
    box_mask.bind(gpu::kBoxMask);
    face_boxes.bind(gpu::kFaceBoxes);
    mesh_pairs.bind(gpu::kBodyPair);
    counters.bind(gpu::kCollisionCounters);
    box_rows.bind(gpu::kBoxRows);
    bvh_nodes.bind(gpu::kBvhNode);
    bvh_boxes.bind(gpu::kBvhBox);
    mesh_bvhs.bind(gpu::kBodyBvh);
    candidates.bind(gpu::kCandidatePair);
    dispatch_args.bind(kDispatchArgsBinding);
    box_pair_list.bind(kBoxPairListBinding);
    bvh_levels.bind(kBvhLevelsBinding);
    touching_pairs.bind(kTouchingPairsBinding);
    bvh_leaves.bind(kBvhLeavesBinding);
  }
};

}  // namespace deformcd::gl
