#pragma once
// Every mesh's BVH on the CPU, kept fitted to the deforming surface: the boxes are refitted
// every pass, and a mesh's tree is rebuilt from its current shape when refitting has loosened
// it too much. When to rebuild is the shared policy of collision::BvhUpkeep
// (core/collision/bvh_upkeep.h), which also holds the trees' topology; the CPU rebuilds a tree
// only when it is about to be traversed.
//
// Thread-to-data mapping of the refit: every tree is cut once (collision::cut_bvh, on upload
// and on a rebuild) into subtrees of at most collision::kBvhCutNodes nodes; one parallel loop
// over all the meshes' subtrees refits each subtree on one thread, children first, and sums its
// internal nodes' areas into the subtree's own slot; then the calling thread refits the few
// nodes above the cut (about one per subtree) and adds the slots in the cut's order. The area
// ratio thus costs no pass of its own (it was 9 % of a bvh pass at 50,000 faces per body), and
// its bits are collision::bvh_area_ratio's whatever the thread count: the cut does not depend
// on it, no slot is shared, and the sums are added in one order.
//
// For the traversal the refit also writes each node's box into its parent's ChildBoxes record
// (the same floats as boxes()): an internal node's two children's boxes side by side, one cache
// line, so that splitting a pair of nodes loads two records where it loaded the two nodes and
// four boxes elsewhere (issue 14: a third of a one-thread pass was the traversal's loads and
// branches). A record is written only by the task refitting the child, or by the calling thread
// for the nodes above the cut.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::cpu {

// An internal node as the traversal reads it: its two children's boxes, per axis side by side
// ([axis][child]), and its children: a leaf as kLeafChild | its global face, an internal node as
// the index of its own record. 64 bytes, one cache line.
struct alignas(64) ChildBoxes {
  float min[3][2];
  float max[3][2];
  std::uint32_t child[2];
  std::uint32_t unused[2];
};
static_assert(sizeof(ChildBoxes) == 64);

// ChildBoxes::child of a leaf: this bit and the leaf's face (faces are fewer than 2^31).
inline constexpr std::uint32_t kLeafChild = 0x80000000u;

// The records of the internal nodes of `nodes`, numbered in node order (record_of: per node its
// record, kBvhInternal for a leaf), each with its children (ChildBoxes::child) and boxes left
// for the caller to write (set_child_box). With `slot_of`, also per node the slot its box takes
// in its parent's record (2 x record + child; kBvhInternal for a root). Throws Error for trees
// over 2^31 faces or more (face_count).
void make_child_records(const std::vector<gpu::BvhNode>& nodes, std::size_t face_count,
                        std::vector<ChildBoxes>& records, std::vector<std::uint32_t>& record_of,
                        std::vector<std::uint32_t>* slot_of = nullptr);

// Box [lo, hi] as child k (0 or 1) of record r.
inline void set_child_box(ChildBoxes& r, std::uint32_t k, const glm::vec3& lo,
                          const glm::vec3& hi) {
  for (int a = 0; a < 3; ++a) {
    r.min[a][k] = lo[a];
    r.max[a][k] = hi[a];
  }
}

class BvhTrees {
 public:
  // Takes the trees of `data` (built on `pose`) and fits them to it.
  void upload(const collision::CollisionData& data, collision::VertexPositions pose);
  // Refits every tree to `positions`, and measures their area ratios.
  void refit(collision::VertexPositions positions);
  // Rebuilds, from `positions` (those of the last refit), the tree of every mesh m with
  // traversed[m] != 0 whose area ratio, measured by the last refit, says it has degraded
  // (collision::BvhUpkeep::degraded), one after the other. Returns how many it rebuilt.
  std::uint32_t rebuild_degraded(const std::vector<std::uint8_t>& traversed,
                                 collision::VertexPositions positions);

  [[nodiscard]] const std::vector<gpu::BvhNode>& nodes() const { return upkeep_.nodes(); }
  [[nodiscard]] const std::vector<gpu::Box>& boxes() const { return boxes_; }
  [[nodiscard]] const gpu::BodyBvh& tree(std::uint32_t mesh) const { return upkeep_.tree(mesh); }
  // One record per internal node (boxes as last refitted), and per node the index of its record
  // (kBvhInternal for a leaf).
  [[nodiscard]] const std::vector<ChildBoxes>& child_boxes() const { return child_boxes_; }
  [[nodiscard]] const std::vector<std::uint32_t>& record_of() const { return record_of_; }
  // The area ratio of `mesh`'s tree as last refitted (or rebuilt), and right after its last
  // build; both collision::bvh_area_ratio's bit for bit.
  [[nodiscard]] double area_ratio(std::uint32_t mesh) const { return ratios_[mesh]; }
  [[nodiscard]] double built_area_ratio(std::uint32_t mesh) const {
    return upkeep_.built_ratio(mesh);
  }
  // Trees rebuilt since upload.
  [[nodiscard]] std::uint64_t rebuild_count() const { return upkeep_.rebuilds(); }
  // The trees' topology, faces and meshes (what a proximity search queries).
  [[nodiscard]] const collision::BvhUpkeep& upkeep() const { return upkeep_; }

 private:
  // One node as the refit reads it, in the nodes' order: a leaf's face corners (vertex indices
  // of its mesh) and mesh, or an internal node's children and kBvhInternal. Made from the nodes
  // and faces on upload and on a rebuild, so that a refit streams one 16-byte array instead of
  // reading each node and then, at a leaf, its face elsewhere (at 50,000 faces per body the
  // trees and faces far exceed the caches: the refit was half of a bvh pass).
  struct RefitNode {
    std::uint32_t x;     // left child, or corner a
    std::uint32_t y;     // right child, or corner b
    std::uint32_t z;     // corner c, or the internal node's record (ChildBoxes)
    std::uint32_t mesh;  // kBvhInternal for an internal node
  };

  // A subtree of a mesh's cut: nodes [first, first + count).
  struct Piece {
    std::uint32_t first;
    std::uint32_t count;
  };

  void make_refit_nodes(std::uint32_t first, std::uint32_t count);
  // The records of every internal node, their children and the slots of every node, with the
  // boxes of boxes_ (on upload and after a rebuild).
  void make_child_boxes();
  // Cuts every mesh's tree into pieces_ and top_nodes_.
  void cut_trees();
  // collision::refit_bvh over refit_nodes_ (the same boxes, bit for bit); returns the summed
  // area of the range's internal nodes, last node to first (collision::bvh_area_ratio's order).
  double refit_range(std::uint32_t first, std::uint32_t count,
                     collision::VertexPositions positions);
  // After its pieces: the mesh's nodes above the cut, and its area ratio into ratios_.
  void refit_top(std::uint32_t mesh);

  collision::BvhUpkeep upkeep_;
  std::vector<gpu::Face> faces_;
  std::vector<RefitNode> refit_nodes_;    // per node
  std::vector<gpu::Box> boxes_;           // per node
  std::vector<ChildBoxes> child_boxes_;   // per internal node, in the nodes' order
  std::vector<std::uint32_t> record_of_;  // per node: its record, kBvhInternal for a leaf
  // Per node: where its box goes in its parent's record (record * 2 + child), kBvhInternal for
  // a root.
  std::vector<std::uint32_t> slots_;
  // The cuts of every mesh's tree, mesh after mesh: mesh m's pieces are
  // pieces_[piece_offset_[m], piece_offset_[m + 1]), its top nodes (preorder) likewise.
  std::vector<Piece> pieces_;
  std::vector<std::uint32_t> piece_offset_;  // per mesh, + 1
  std::vector<std::uint32_t> top_nodes_;
  std::vector<std::uint32_t> top_offset_;  // per mesh, + 1
  std::vector<double> piece_areas_;        // per piece, this pass
  std::vector<double> ratios_;             // per mesh: its area ratio, this pass
};

}  // namespace deformcd::cpu
