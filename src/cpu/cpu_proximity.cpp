#include "cpu_proximity.h"

#include <algorithm>

#include "core/collision/bvh.h"
#include "parallel_for.h"

namespace deformcd::cpu {

CpuProximity::CpuProximity(const collision::CollisionData& data, std::shared_ptr<Executor> executor)
    : data_(data),
      owners_(collision::primitive_owners(data.faces)),
      executor_(std::move(executor)) {}

void CpuProximity::refit(collision::VertexPositions positions, collision::VertexPositions motion) {
  if (!built_) {
    collision::build_hierarchies(data_, positions);
    upkeep_.reset(data_, positions);
    boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
    built_ = true;
  }
  // The upkeep rule judges the tree on the period's start; a swept box is the union of the
  // boxes at both ends (a box union is exact), so the end's refit is merged in afterwards.
  for (std::uint32_t m = 0; m < data_.mesh_count(); ++m) {
    const gpu::BodyBvh& tree = upkeep_.tree(m);
    collision::refit_bvh(upkeep_.nodes(), tree.root, tree.node_count, positions, data_.faces,
                         boxes_);
    if (upkeep_.degraded(m, upkeep_.area_ratio(m, boxes_))) upkeep_.rebuild(m, positions, boxes_);
  }
  if (motion == nullptr) return;
  ends_.resize(data_.mesh_count());
  std::vector<collision::MeshVertices> end(data_.mesh_count());
  for (std::uint32_t m = 0; m < data_.mesh_count(); ++m) {
    const std::uint32_t vertices = data_.meshes[m].vertex_count;
    ends_[m].resize(vertices);
    parallel_for(vertices, [&](std::size_t v) {
      const auto i = static_cast<std::uint32_t>(v);
      ends_[m][v] =
          collision::vertex_position(positions, m, i) + collision::vertex_position(motion, m, i);
    });
    end[m] = {&ends_[m][0].x, 3u};
  }
  end_boxes_.resize(boxes_.size());
  for (std::uint32_t m = 0; m < data_.mesh_count(); ++m) {
    const gpu::BodyBvh& tree = upkeep_.tree(m);
    collision::refit_bvh(upkeep_.nodes(), tree.root, tree.node_count, end.data(), data_.faces,
                         end_boxes_);
  }
  parallel_for(boxes_.size(), [&](std::size_t i) {
    boxes_[i].min = glm::min(boxes_[i].min, end_boxes_[i].min);
    boxes_[i].max = glm::max(boxes_[i].max, end_boxes_[i].max);
  });
}

std::vector<collision::ProximityCandidate> CpuProximity::find(collision::VertexPositions positions,
                                                              collision::VertexPositions motion,
                                                              std::span<const float> reach) {
  std::vector<collision::ProximityCandidate> all;
  executor_->run([&] {
    refit(positions, motion);
    for (const gpu::BodyPair& pair : data_.mesh_pairs) {
      const gpu::MeshInfo& mesh_a = data_.meshes[pair.a];
      const gpu::BodyBvh& tree_b = upkeep_.tree(pair.b);
      const float grow = reach[pair.a] + reach[pair.b];
      const bool self = pair.a == pair.b;
      std::vector<std::vector<collision::ProximityCandidate>> per_face(mesh_a.face_count);
      parallel_for(
          mesh_a.face_count,
          [&](std::size_t i) {
            const std::uint32_t index_a = mesh_a.face_offset + static_cast<std::uint32_t>(i);
            const gpu::Face& fa = data_.faces[index_a];
            glm::vec3 xa[6];
            collision::swept_face_vertices(positions, motion, fa, xa);
            const gpu::Box query = collision::reach_box(xa, 6u, grow);
            auto& out = per_face[i];
            collision::query_bvh(
                upkeep_.nodes().data(), boxes_.data(), tree_b.root, query,
                [&](std::uint32_t index_b) {
                  const gpu::Face& fb = data_.faces[index_b];
                  if (self && (index_b <= index_a || collision::faces_share_vertex(fa, fb))) return;
                  collision::emit_face_pair_candidates(
                      positions, motion, fa, index_a, owners_[index_a], fb, index_b,
                      owners_[index_b], grow,
                      [&](const collision::ProximityCandidate& c) { out.push_back(c); });
                });
          },
          64);
      std::size_t total = all.size();
      for (const auto& list : per_face)
        total += list.size();
      all.reserve(total);
      for (const auto& list : per_face)
        all.insert(all.end(), list.begin(), list.end());
    }
  });
  return all;
}

}  // namespace deformcd::cpu
