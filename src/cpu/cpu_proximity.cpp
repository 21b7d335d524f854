#include "cpu_proximity.h"

#include <algorithm>

#include "core/collision/bvh.h"
#include "parallel_for.h"

namespace deformcd::cpu {

CpuProximity::CpuProximity(const collision::CollisionData& data, std::shared_ptr<Executor> executor)
    : data_(data),
      owners_(collision::primitive_owners(data.faces)),
      executor_(std::move(executor)) {}

void CpuProximity::refit(collision::VertexPositions positions, collision::VertexPositions motion,
                         collision::VertexReach reach) {
  if (!built_) {
    collision::build_hierarchies(data_, positions);
    upkeep_.reset(data_, positions);
    boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
    built_ = true;
  }
  // The upkeep rule judges each tree on the period's start, as the detector's trees are judged;
  // the search then refits the boxes it queries: each leaf its face's swept box grown by the
  // face's reach, each parent the union of its children, in reverse preorder.
  const std::vector<gpu::BvhNode>& nodes = upkeep_.nodes();
  for (std::uint32_t m = 0; m < data_.mesh_count(); ++m) {
    const gpu::BodyBvh& tree = upkeep_.tree(m);
    collision::refit_bvh(nodes, tree.root, tree.node_count, positions, data_.faces, boxes_);
    if (upkeep_.degraded(m, upkeep_.area_ratio(m, boxes_))) upkeep_.rebuild(m, positions, boxes_);
    for (std::uint32_t i = tree.root + tree.node_count; i-- > tree.root;) {
      const gpu::BvhNode& n = nodes[i];
      if (n.face != gpu::kBvhInternal) {
        const gpu::Face& f = data_.faces[n.face];
        glm::vec3 x[6];
        float corner[3];
        collision::swept_face_vertices(positions, motion, f, x);
        boxes_[i] = collision::reach_box(x, 6u, collision::face_reaches(reach, f, corner));
      } else {
        const gpu::Box& l = boxes_[n.left];
        const gpu::Box& r = boxes_[n.right];
        boxes_[i] = {glm::min(l.min, r.min), glm::max(l.max, r.max)};
      }
    }
  }
}

std::vector<collision::ProximityCandidate> CpuProximity::find(collision::VertexPositions positions,
                                                              collision::VertexPositions motion,
                                                              collision::VertexReach reach,
                                                              std::vector<float>* distances) {
  std::vector<collision::ProximityCandidate> all;
  if (distances != nullptr) distances->clear();
  executor_->run([&] {
    refit(positions, motion, reach);
    for (const gpu::BodyPair& pair : data_.mesh_pairs) {
      const gpu::MeshInfo& mesh_a = data_.meshes[pair.a];
      const gpu::BodyBvh& tree_b = upkeep_.tree(pair.b);
      const bool self = pair.a == pair.b;
      // Fixed chunks of faces, each with its own lists, joined in chunk order: the order does
      // not depend on the schedule, and a face costs no allocation of its own.
      constexpr std::size_t kChunk = 64;
      const std::size_t chunks = (mesh_a.face_count + kChunk - 1) / kChunk;
      std::vector<std::vector<collision::ProximityCandidate>> per_chunk(chunks);
      std::vector<std::vector<float>> per_chunk_distance(chunks);
      parallel_for(
          chunks,
          [&](std::size_t chunk) {
            auto& out = per_chunk[chunk];
            auto& out_distance = per_chunk_distance[chunk];
            const std::size_t end = std::min<std::size_t>((chunk + 1) * kChunk, mesh_a.face_count);
            for (std::size_t i = chunk * kChunk; i < end; ++i) {
              const std::uint32_t index_a = mesh_a.face_offset + static_cast<std::uint32_t>(i);
              const gpu::Face& fa = data_.faces[index_a];
              glm::vec3 xa[6];
              float corner[3];
              collision::swept_face_vertices(positions, motion, fa, xa);
              const gpu::Box query =
                  collision::reach_box(xa, 6u, collision::face_reaches(reach, fa, corner));
              // Within one mesh each face pair once (a face with itself pairs only surface
              // neighbours, which the emit leaves out).
              collision::query_bvh(
                  upkeep_.nodes().data(), boxes_.data(), tree_b.root, query,
                  [&](std::uint32_t index_b) {
                    if (self && index_b <= index_a) return;
                    collision::emit_face_pair_candidates(
                        positions, motion, reach, fa, index_a, owners_[index_a],
                        data_.faces[index_b], index_b, owners_[index_b],
                        [&](const collision::ProximityCandidate& c, float distance) {
                          out.push_back(c);
                          out_distance.push_back(distance);
                        });
                  });
            }
          },
          1);
      std::size_t total = all.size();
      for (const auto& list : per_chunk)
        total += list.size();
      all.reserve(total);
      for (const auto& list : per_chunk)
        all.insert(all.end(), list.begin(), list.end());
      if (distances != nullptr) {
        distances->reserve(total);
        for (const auto& list : per_chunk_distance)
          distances->insert(distances->end(), list.begin(), list.end());
      }
    }
  });
  return all;
}

}  // namespace deformcd::cpu
