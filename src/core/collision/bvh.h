#pragma once
// Bounding volume hierarchies over a body's surface faces (one face per leaf), for the `bvh`
// broad phase (beyond the paper). The tree's topology is built once on the rest pose (and again
// when refitting has degraded it); every frame only the boxes are refitted, bottom-up, from the
// faces' current vertices. Box unions are min/max of the same floats, so every box is exact and
// the broad phase loses no pair that the narrow phase's exact box test would keep.

#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/broad_phase.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Longest root-to-leaf path a traversal stack must hold (a median split keeps the depth at
/// ceil(log2(faces)) + 1, so 64 holds any mesh that fits in memory).
inline constexpr std::uint32_t kBvhMaxDepth = 64;

/// Both backends rebuild a body's tree when its area ratio (bvh_area_ratio) exceeds this factor
/// times the ratio right after its last build. A rebuild of a 5k-face body costs about one bvh
/// pass in contact; at 1.5 the looser traversal has paid for it within a few frames, while a
/// factor near 1 would rebuild on every wobble. The shipped scenes stay within 0.96-1.02.
inline constexpr double kBvhRebuildFactor = 1.5;

/// Builds the BVH of faces [face_offset, face_offset + face_count) (vertices at `positions`)
/// top-down: each node's faces are split at the median of their centroids along the longest
/// axis of the centroids' bounds. Nodes in preorder, numbered from node_offset. Throws Error for
/// zero faces.
[[nodiscard]] std::vector<gpu::BvhNode> build_bvh(VertexPositions positions,
                                                  const std::vector<gpu::Face>& faces,
                                                  std::uint32_t face_offset,
                                                  std::uint32_t face_count,
                                                  std::uint32_t node_offset);

/// Depth (edges on the longest root-to-leaf path) of the tree rooted at `root`.
[[nodiscard]] std::uint32_t bvh_depth(const std::vector<gpu::BvhNode>& nodes, std::uint32_t root);

/// Subtrees of at most this many nodes are the units a tree is cut into (cut_bvh): refitted one
/// per task by the CPU backend, and the pieces of the area ratio's sum. A node's refit is a few
/// loads and six min/max (a few ns), so a piece of 512-1024 nodes is a few microseconds of
/// work, well above a oneTBB task's cost, while a 50,000-face tree still gives about 130 pieces
/// to share out. A constant, not a function of the thread count: the area ratio's summation
/// order (hence its bits) depends on the cut.
inline constexpr std::uint32_t kBvhCutNodes = 1024;

/// A tree cut into independent subtrees and the internal nodes above them. Preorder puts a
/// subtree in one range of nodes ([root, root + count)), and a node's box depends only on its
/// subtree's, so the subtrees can be refitted in any order or at once, and then the top nodes,
/// children before parents.
struct BvhCut {
  /// Internal nodes above the cut, in preorder (a parent before its children).
  std::vector<std::uint32_t> top;
  /// The subtrees below the cut, each (its first node, its node count), in preorder of their
  /// first nodes; together with `top` they hold every node of the tree once.
  std::vector<glm::uvec2> subtrees;
};

/// Cuts the tree of nodes [first, first + count) (first its root) below every node whose
/// subtree has more than `max_nodes` nodes. Depends on the topology only.
[[nodiscard]] BvhCut cut_bvh(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first,
                             std::uint32_t count, std::uint32_t max_nodes = kBvhCutNodes);

/// Recomputes the boxes of nodes [first, first + count) in reverse preorder (children first):
/// leaves from their face's vertices, internal nodes as the union of their children.
void refit_bvh(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first, std::uint32_t count,
               VertexPositions positions, const std::vector<gpu::Face>& faces,
               std::vector<gpu::Box>& boxes);

/// Calls visit(face) for every leaf of the tree at `root` whose box overlaps `query` (closed
/// boxes), depth first with an explicit stack (mirrored in shaders/collision/bvh.glsl).
template <class Visit>
void query_bvh(const gpu::BvhNode* nodes, const gpu::Box* boxes, std::uint32_t root,
               const gpu::Box& query, const Visit& visit) {
  std::uint32_t stack[kBvhMaxDepth + 1];
  std::uint32_t size = 0;
  stack[size++] = root;
  while (size > 0) {
    const std::uint32_t i = stack[--size];
    if (!boxes_overlap(boxes[i], query)) continue;
    const gpu::BvhNode& n = nodes[i];
    if (n.face != gpu::kBvhInternal) {
      visit(n.face);
    } else {
      stack[size++] = n.right;
      stack[size++] = n.left;
    }
  }
}

/// Surface area of a box, in double (0 for an empty one).
[[nodiscard]] inline double box_area(const gpu::Box& b) {
  const glm::dvec3 e = glm::max(glm::dvec3(b.max) - glm::dvec3(b.min), glm::dvec3(0.0));
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

/// How loose a refitted tree has become: the summed surface area of its internal nodes over the
/// root's (scale-free; grows as deformation makes siblings overlap). Compare with the value
/// right after a build to decide on a rebuild. The sum has one order, so that a parallel
/// evaluation gives the same bits: per subtree of cut_bvh(nodes, first, count), in the cut's
/// order, its internal nodes' areas summed from its last node down to its first, starting from
/// 0; those sums added in the cut's order; then the top nodes' areas, last to first.
[[nodiscard]] double bvh_area_ratio(const std::vector<gpu::BvhNode>& nodes, std::uint32_t first,
                                    std::uint32_t count, const std::vector<gpu::Box>& boxes);

}  // namespace deformcd::collision
