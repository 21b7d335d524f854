#include "cpu_bvh_broad_phase.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/collision/body_pairs.h"
#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"

namespace deformcd::cpu {

namespace {

// Query faces per task: a query costs a few dozen box tests when it hits the other body and
// one when it misses, so a task needs many of them to outweigh its scheduling.
constexpr std::size_t kQueryGrain = 64;

// The tree traversed for a mesh pair: the one of the mesh with more faces (b on a tie), so
// that the fewer faces of the other make the queries (log of the larger count per query).
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

void BvhBroadPhase::run(collision::VertexPositions positions, const std::vector<gpu::Face>& faces,
                        const NarrowPhase& narrow, PairCollector& out) {
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
  for (std::uint32_t mesh = 0; mesh < queried_.size(); ++mesh) {
    if (queried_[mesh] != 0u) trees_.rebuild_if_degraded(mesh, positions);
  }
  for (const gpu::BodyPair& pair : touching_) {
    const std::uint32_t tree = traversed_mesh(pair, meshes_);
    traverse(pair, tree == pair.a ? pair.b : pair.a, tree, positions, faces, narrow, out);
  }
}

void BvhBroadPhase::traverse(const gpu::BodyPair& pair, std::uint32_t query_body,
                             std::uint32_t tree_body, collision::VertexPositions positions,
                             const std::vector<gpu::Face>& faces, const NarrowPhase& narrow,
                             PairCollector& out) const {
  const gpu::MeshInfo& q = meshes_[query_body];
  const std::uint32_t root = trees_.tree(tree_body).root;
  const gpu::BvhNode* nodes = trees_.nodes().data();
  const gpu::Box* boxes = trees_.boxes().data();
  const bool query_is_a = query_body == pair.a;
  // Ranges rather than parallel_for.h's single elements: the thread's result list is looked up
  // once per range, not once per query.
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, q.face_count, kQueryGrain),
                    [&](const tbb::blocked_range<std::uint32_t>& range) {
                      ThreadPairs& local = out.local();
                      for (std::uint32_t i = range.begin(); i != range.end(); ++i) {
                        const std::uint32_t face = q.face_offset + i;
                        const gpu::Face& f = faces[face];
                        gpu::Box box = collision::empty_box();
                        glm::vec3 corners[3];
                        collision::face_vertices(positions, f, corners);
                        collision::grow_box(box, corners[0]);
                        collision::grow_box(box, corners[1]);
                        collision::grow_box(box, corners[2]);
                        // The test is fused into the traversal: no candidate list to write and read
                        // back.
                        collision::query_bvh(nodes, boxes, root, box, [&](std::uint32_t other) {
                          if (query_is_a) {
                            narrow.test(face, other, local);
                          } else {
                            narrow.test(other, face, local);
                          }
                        });
                      }
                    });
}

}  // namespace deformcd::cpu
