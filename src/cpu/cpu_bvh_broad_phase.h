#pragma once
// The `bvh` broad phase on the CPU (beyond the paper): per mesh a BVH over its faces,
// refitted every pass (cpu_bvh_trees.h); body pairs whose root boxes overlap are traversed, both
// trees descended together (cpu_bvh_pair_traversal.h), and every face pair whose boxes overlap
// goes straight to the exact triangle test. A body colliding with itself descends its tree
// against itself, meeting each pair of faces once.
//
// Exactness: tri_tri_intersect rejects a pair whose float bounding boxes are apart, and every
// BVH box is the exact min/max of the same floats, so culling by closed-box overlap loses no
// pair that the all-pairs baseline reports; each face pair is met once (one face per leaf).

#include <cstdint>
#include <vector>

#include "cpu/cpu_bvh_pair_traversal.h"
#include "cpu/cpu_bvh_trees.h"
#include "cpu/cpu_narrow_phase.h"

namespace deformcd::cpu {

class BvhBroadPhase {
 public:
  // Takes the meshes, their pairs and trees (built on `pose`).
  void upload(const collision::CollisionData& data, collision::VertexPositions pose);
  // One pass: refits the trees, rebuilds the degraded ones about to be traversed, and tests
  // the face pairs of the mesh pairs whose boxes overlap.
  void run(collision::VertexPositions positions, const NarrowPhase& narrow, PairCollector& out);

  [[nodiscard]] const BvhTrees& trees() const { return trees_; }
  // Fits the trees to `positions` as a pass does before a query of the trees of the meshes
  // m with queried[m] != 0 (a proximity search's): refits them all, rebuilds the degraded
  // ones among those.
  void fit_trees(collision::VertexPositions positions, const std::vector<std::uint8_t>& queried);

 private:
  // The tree of pair.a against the tree of pair.b, in parallel over pieces of the traversal.
  void traverse(const gpu::BodyPair& pair, const NarrowPhase& narrow, PairCollector& out);

  BvhTrees trees_;
  std::vector<gpu::MeshInfo> meshes_;
  std::vector<gpu::BodyPair> pairs_;     // the mesh pairs to test, sorted
  std::vector<gpu::BodyPair> touching_;  // mesh pairs to traverse this pass
  std::vector<gpu::Box> root_boxes_;     // per mesh, this pass
  std::vector<std::uint8_t> queried_;    // per mesh: its tree is traversed this pass
  std::vector<NodePair> frontier_;       // one traversal cut into pieces
  std::vector<NodePair> scratch_;
};

}  // namespace deformcd::cpu
