#include "cpu/cpu_bvh_broad_phase.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/collision/body_pairs.h"
#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"

namespace deformcd::cpu {

namespace {

// Node pairs per thread a mesh pair's traversal is cut into before the threads take them:
// enough to share out pieces of very different sizes, few enough that cutting them (a few box
// tests each, on one thread) stays small. One thread takes the traversal whole.
constexpr std::size_t kFrontierPairsPerThread = 64;

// The tree of a mesh pair that is rebuilt when degraded: the one of the mesh with more faces
// (b on a tie). Both trees are descended, but the policy is the GL backend's, whose faces of the
// smaller mesh query the larger one's tree (bvh_traverse.comp): a loose tree costs time only,
// never a pair, since every box stays exact.
std::uint32_t traversed_mesh(const gpu::BodyPair& pair, const std::vector<gpu::MeshInfo>& meshes) {
  return meshes[pair.a].face_count > meshes[pair.b].face_count ? pair.a : pair.b;
}

bool listed(const std::vector<gpu::BodyPair>& sorted_pairs, const gpu::BodyPair& pair) {
  return std::binary_search(sorted_pairs.begin(), sorted_pairs.end(), pair,
                            [](const gpu::BodyPair& x, const gpu::BodyPair& y) {
                              return x.a < y.a || (x.a == y.a && x.b < y.b);
                            });
}

}  // namespace

void BvhBroadPhase::upload(const collision::CollisionData& data, collision::VertexPositions pose) {
  trees_.upload(data, pose);
  meshes_ = data.meshes;
  pairs_ = data.mesh_pairs;
  touching_.clear();
  touching_.reserve(pairs_.size());
  queried_.assign(meshes_.size(), 0u);
}

void BvhBroadPhase::run(collision::VertexPositions positions, const NarrowPhase& narrow,
                        PairCollector& out) {
  trees_.refit(positions);
  std::fill(queried_.begin(), queried_.end(), 0u);
  // Mesh level: sort and sweep over the root boxes, so that many meshes cost what their nearby
  // pairs cost; it returns the pairs of different meshes whose roots touch, in (a, b) order,
  // of which those listed to be tested are kept. A mesh colliding with itself (a pair (m, m))
  // is traversed against its own tree.
  root_boxes_.resize(meshes_.size());
  for (std::uint32_t mesh = 0; mesh < meshes_.size(); ++mesh) {
    root_boxes_[mesh] = trees_.boxes()[trees_.tree(mesh).root];
  }
  touching_.clear();
  for (const gpu::BodyPair& pair : collision::overlapping_body_pairs(root_boxes_)) {
    if (listed(pairs_, pair)) touching_.push_back(pair);
  }
  for (const gpu::BodyPair& pair : pairs_) {
    if (pair.a == pair.b) touching_.push_back(pair);
  }
  for (const gpu::BodyPair& pair : touching_)
    queried_[traversed_mesh(pair, meshes_)] = 1u;
  // A tree nobody traverses may stay loose: its root box, all that is read of it, is exact.
  trees_.rebuild_degraded(queried_, positions);
  for (const gpu::BodyPair& pair : touching_)
    traverse(pair, narrow, out);
}

void BvhBroadPhase::fit_trees(collision::VertexPositions positions,
                              const std::vector<std::uint8_t>& queried) {
  trees_.refit(positions);
  trees_.rebuild_degraded(queried, positions);
}

void BvhBroadPhase::traverse(const gpu::BodyPair& pair, const NarrowPhase& narrow,
                             PairCollector& out) {
  const gpu::BvhNode* nodes = trees_.nodes().data();
  const gpu::Box* boxes = trees_.boxes().data();
  const TraversalTrees trees{nodes, boxes, trees_.child_boxes().data(), trees_.record_of().data()};
  const std::uint32_t root_a = trees_.tree(pair.a).root;
  const std::uint32_t root_b = trees_.tree(pair.b).root;
  const bool self = pair.a == pair.b;
  if (!collision::boxes_overlap(boxes[root_a], boxes[root_b])) return;
  frontier_.assign(1, NodePair{root_a, root_b});
  const auto threads = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
  if (threads > 1) {
    expand_frontier(nodes, boxes, self, kFrontierPairsPerThread * threads, frontier_, scratch_);
  }
  // The pieces differ in size by orders of magnitude (most are a few leaf pairs, some hold the
  // whole contact): one piece per task, taken by whichever thread is free.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, frontier_.size(), 1),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      ThreadPairs& local = out.local();
                      CandidateBatch batch;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        // The tests are fused into the traversal, in batches: no candidate list
                        // to write and read back. Within one mesh the narrow phase takes the
                        // lower face first.
                        traverse_node_pair(trees, self, frontier_[i],
                                           [&](std::uint32_t face_a, std::uint32_t face_b) {
                                             if (self && face_b < face_a) {
                                               narrow.add(face_b, face_a, batch, local);
                                             } else {
                                               narrow.add(face_a, face_b, batch, local);
                                             }
                                           });
                      }
                      narrow.flush(batch, local);
                    });
}

}  // namespace deformcd::cpu
