#include "cpu_proximity.h"

#include <algorithm>

#include "core/collision/bvh.h"
#include "parallel_for.h"

namespace deformcd::cpu {

CpuProximity::CpuProximity(const collision::CollisionData& data, std::shared_ptr<Executor> executor)
    : data_(data),
      owners_(collision::primitive_owners(data.faces)),
      executor_(std::move(executor)) {}

void CpuProximity::refit(collision::VertexPositions positions) {
  if (!built_) {
    collision::build_hierarchies(data_, positions);
    upkeep_.reset(data_, positions);
    boxes_.assign(upkeep_.nodes().size(), gpu::Box{});
    built_ = true;
  }
  for (std::uint32_t m = 0; m < data_.mesh_count(); ++m) {
    const gpu::BodyBvh& tree = upkeep_.tree(m);
    collision::refit_bvh(upkeep_.nodes(), tree.root, tree.node_count, positions, data_.faces,
                         boxes_);
    if (upkeep_.degraded(m, upkeep_.area_ratio(m, boxes_))) upkeep_.rebuild(m, positions, boxes_);
  }
}

std::vector<collision::ProximityCandidate> CpuProximity::find(collision::VertexPositions positions,
                                                              std::span<const float> reach,
                                                              std::span<const glm::vec3> drift) {
  std::vector<collision::ProximityCandidate> all;
  executor_->run([&] {
    refit(positions);
    for (const gpu::BodyPair& pair : data_.mesh_pairs) {
      const gpu::MeshInfo& mesh_a = data_.meshes[pair.a];
      const gpu::BodyBvh& tree_b = upkeep_.tree(pair.b);
      const float grow = reach[pair.a] + reach[pair.b];
      const bool self = pair.a == pair.b;
      const glm::vec3 sweep = drift[pair.a] - drift[pair.b];
      std::vector<std::vector<collision::ProximityCandidate>> per_face(mesh_a.face_count);
      parallel_for(
          mesh_a.face_count,
          [&](std::size_t i) {
            const std::uint32_t index_a = mesh_a.face_offset + static_cast<std::uint32_t>(i);
            const gpu::Face& fa = data_.faces[index_a];
            glm::vec3 xa[3];
            collision::face_vertices(positions, fa, xa);
            const gpu::Box query = collision::sweep_box(collision::reach_box(xa, 3u, grow), sweep);
            auto& out = per_face[i];
            collision::query_bvh(
                upkeep_.nodes().data(), boxes_.data(), tree_b.root, query,
                [&](std::uint32_t index_b) {
                  const gpu::Face& fb = data_.faces[index_b];
                  if (self && (index_b <= index_a || collision::faces_share_vertex(fa, fb))) return;
                  collision::emit_face_pair_candidates(
                      positions, fa, index_a, owners_[index_a], fb, index_b, owners_[index_b], grow,
                      sweep, [&](const collision::ProximityCandidate& c) { out.push_back(c); });
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
  std::sort(all.begin(), all.end());
  return all;
}

}  // namespace deformcd::cpu
