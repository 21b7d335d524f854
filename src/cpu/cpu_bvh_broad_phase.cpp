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

// The tree traversed for a body pair: the one of the body with more faces (b on a tie), so
// that the fewer faces of the other make the queries (log of the larger count per query).
std::uint32_t traversed_body(const gpu::BodyPair& pair,
                             const std::vector<gpu::ObjectInfo>& objects) {
  return objects[pair.a].face_count > objects[pair.b].face_count ? pair.a : pair.b;
}

}  // namespace

void BvhBroadPhase::upload(const WorldState& state) {
  trees_.upload(state);
  objects_ = state.objects;
  touching_.clear();
  touching_.reserve(state.body_pairs.size());
  queried_.assign(state.objects.size(), 0u);
  self_pairs_.clear();
  for (const gpu::BodyPair& pair : state.body_pairs) {
    if (pair.a == pair.b) self_pairs_.push_back(pair);
  }
}

void BvhBroadPhase::run(const std::vector<glm::vec4>& positions,
                        const std::vector<gpu::Face>& faces,
                        const std::vector<gpu::BodyPair>& body_pairs, const NarrowPhase& narrow,
                        PairCollector& out) {
  trees_.refit(positions, faces);
  std::fill(queried_.begin(), queried_.end(), 0u);
  // Body level: sort and sweep over the root boxes, so that many bodies cost what their
  // nearby pairs cost. Every pair of different bodies is a candidate here (body_pairs lists
  // them all); the sweep returns those whose roots touch, in (a, b) order. A body colliding
  // with itself (a pair (b, b) in body_pairs) is traversed against its own tree.
  (void)body_pairs;
  root_boxes_.resize(objects_.size());
  for (std::uint32_t body = 0; body < objects_.size(); ++body) {
    root_boxes_[body] = trees_.boxes()[trees_.tree(body).root];
  }
  touching_ = collision::overlapping_body_pairs(root_boxes_);
  touching_.insert(touching_.end(), self_pairs_.begin(), self_pairs_.end());
  for (const gpu::BodyPair& pair : touching_)
    queried_[traversed_body(pair, objects_)] = 1u;
  // A tree nobody traverses may stay loose: its root box, all that is read of it, is exact.
  for (std::uint32_t body = 0; body < queried_.size(); ++body) {
    if (queried_[body] != 0u) trees_.rebuild_if_degraded(body, positions, faces);
  }
  for (const gpu::BodyPair& pair : touching_) {
    const std::uint32_t tree = traversed_body(pair, objects_);
    traverse(pair, tree == pair.a ? pair.b : pair.a, tree, positions, faces, narrow, out);
  }
}

void BvhBroadPhase::traverse(const gpu::BodyPair& pair, std::uint32_t query_body,
                             std::uint32_t tree_body, const std::vector<glm::vec4>& positions,
                             const std::vector<gpu::Face>& faces, const NarrowPhase& narrow,
                             PairCollector& out) const {
  const gpu::ObjectInfo& q = objects_[query_body];
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
                        collision::grow_box(box, glm::vec3(positions[f.a]));
                        collision::grow_box(box, glm::vec3(positions[f.b]));
                        collision::grow_box(box, glm::vec3(positions[f.c]));
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
