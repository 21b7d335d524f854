#pragma once
// The orders in which GlCollision's bvh shaders take the BVH nodes, derived from the trees'
// topology on the host at upload and after each rebuild (the only times it changes). No GL here.
//   refit      the internal nodes level by level, deepest first, every mesh's nodes of one depth
//              in one dispatch (bvh_refit_level.comp): a node's children are always written by
//              an earlier dispatch;
//   traversal  each mesh's leaves in preorder (bvh_traverse.comp): neighbouring lanes then query
//              with neighbouring faces.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

struct BvhWorkOrder {
  // The internal nodes (global indices) of every tree, by depth, deepest first; within a depth,
  // in increasing index order.
  std::vector<std::uint32_t> refit_order;
  // Per depth, deepest first: (first entry in refit_order, count). Depths without internal
  // nodes are left out.
  std::vector<glm::uvec2> levels;
  // Per mesh, from its face offset: its tree's leaves in preorder (neighbouring leaves hold
  // neighbouring faces), one per face.
  std::vector<std::uint32_t> leaves;
};

// The orders of the trees `trees` (one per mesh of `meshes`) over `nodes`, preorder per tree
// (as check_collision_data makes sure), among `face_count` faces.
[[nodiscard]] BvhWorkOrder plan_bvh_work_order(const std::vector<gpu::BvhNode>& nodes,
                                               const std::vector<gpu::BodyBvh>& trees,
                                               const std::vector<gpu::MeshInfo>& meshes,
                                               std::size_t face_count);

}  // namespace deformcd::gl
