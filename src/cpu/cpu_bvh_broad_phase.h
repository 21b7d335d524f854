#pragma once
// The `bvh` broad phase on the CPU (beyond the paper): per mesh a BVH over its faces,
// refitted every pass (cpu_bvh_trees.h); body pairs whose root boxes overlap are traversed, the
// faces of the body with fewer faces each querying the tree of the other, and every face pair
// whose boxes overlap goes straight to the exact triangle test. A body colliding with itself
// queries its own tree with each of its faces (the narrow phase keeps one order of each pair).
//
// Exactness: tri_tri_intersect rejects a pair whose float bounding boxes are apart, and every
// BVH box is the exact min/max of the same floats, so culling by closed-box overlap loses no
// pair that the all-pairs baseline reports; each face pair is met once (one face per leaf).

#include <cstdint>
#include <vector>

#include "cpu_bvh_trees.h"
#include "cpu_narrow_phase.h"

namespace deformcd::cpu {

class BvhBroadPhase {
 public:
  // Takes the meshes, their pairs and trees (built on `pose`).
  void upload(const collision::CollisionData& data, collision::VertexPositions pose);
  // One pass: refits the trees, rebuilds the degraded ones about to be traversed, and tests
  // the face pairs of the mesh pairs whose boxes overlap.
  void run(collision::VertexPositions positions, const std::vector<gpu::Face>& faces,
           const NarrowPhase& narrow, PairCollector& out);

  [[nodiscard]] const BvhTrees& trees() const { return trees_; }

 private:
  // The faces of `query_body` against the tree of `tree_body`.
  void traverse(const gpu::BodyPair& pair, std::uint32_t query_body, std::uint32_t tree_body,
                collision::VertexPositions positions, const std::vector<gpu::Face>& faces,
                const NarrowPhase& narrow, PairCollector& out) const;

  BvhTrees trees_;
  std::vector<gpu::MeshInfo> meshes_;
  std::vector<gpu::BodyPair> pairs_;     // the mesh pairs to test, sorted
  std::vector<gpu::BodyPair> touching_;  // mesh pairs to traverse this pass
  std::vector<gpu::Box> root_boxes_;     // per mesh, this pass
  std::vector<std::uint8_t> queried_;    // per mesh: its tree is traversed this pass
};

}  // namespace deformcd::cpu
