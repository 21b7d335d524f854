#include "deformcd/intersection_census.h"

#include <algorithm>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "detector/closed_surface_inside.h"

namespace deformcd {

struct IntersectionCounter::Impl {
  std::vector<CollisionMesh> meshes;
  Detector detector;
  std::vector<bool> closed;
  /// Per mesh: its surface vertices (its triangles' corners), ascending.
  std::vector<std::vector<std::uint32_t>> surface_vertices;

  Impl(std::vector<CollisionMesh> with_self, int threads)
      : meshes(with_self),
        detector(
            std::move(with_self),
            {.backend = BackendKind::kCpu, .broadphase = BroadPhase::kBvh, .threads = threads}) {
    for (const CollisionMesh& mesh : meshes) {
      closed.push_back(collision::surface_closed(mesh.triangles));
      surface_vertices.push_back(collision::surface_vertices(mesh.triangles));
    }
  }
};

namespace {

std::vector<CollisionMesh> with_self_collision(std::vector<CollisionMesh> meshes) {
  for (CollisionMesh& mesh : meshes)
    mesh.self_collision = true;
  return meshes;
}

}  // namespace

IntersectionCounter::IntersectionCounter(std::vector<CollisionMesh> meshes, int threads)
    : impl_(std::make_unique<Impl>(with_self_collision(std::move(meshes)), threads)) {}

IntersectionCounter::~IntersectionCounter() = default;
IntersectionCounter::IntersectionCounter(IntersectionCounter&&) noexcept = default;
IntersectionCounter& IntersectionCounter::operator=(IntersectionCounter&&) noexcept = default;

std::size_t IntersectionCounter::mesh_count() const {
  return impl_->meshes.size();
}

bool IntersectionCounter::closed(std::size_t mesh) const {
  return impl_->closed.at(mesh);
}

IntersectionCensus IntersectionCounter::count(
    std::span<const std::span<const glm::vec3>> positions) {
  const std::vector<CollisionMesh>& meshes = impl_->meshes;
  if (positions.size() != meshes.size())
    throw InputError("IntersectionCounter::count",
                     "positions for " + std::to_string(positions.size()) + " meshes, expected " +
                         std::to_string(meshes.size()));
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (positions[m].size() != meshes[m].vertex_count)
      throw InputError("IntersectionCounter::count",
                       "mesh " + std::to_string(m) + " has " + std::to_string(positions[m].size()) +
                           " positions, expected " + std::to_string(meshes[m].vertex_count));
    impl_->detector.set_positions(m, positions[m]);
  }
  impl_->detector.detect();  // checks that every position is finite
  IntersectionCensus census;
  for (const Contact& contact : impl_->detector.contacts()) {
    if (contact.a.body == contact.b.body) {
      ++census.self_pairs;
    } else {
      ++census.between_pairs;
    }
  }
  // Each mesh's surface vertices against every other closed mesh; a vertex inside two meshes
  // counts once.
  std::vector<std::vector<std::uint8_t>> inside(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m)
    inside[m].assign(impl_->surface_vertices[m].size(), 0u);
  for (std::size_t container = 0; container < meshes.size(); ++container) {
    if (!impl_->closed[container]) continue;
    const collision::ClosedSurfaceInside surface(positions[container], meshes[container].triangles);
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      if (m == container) continue;
      const std::vector<std::uint32_t>& vertices = impl_->surface_vertices[m];
      for (std::size_t i = 0; i < vertices.size(); ++i)
        if (inside[m][i] == 0u && surface.inside(positions[m][vertices[i]])) inside[m][i] = 1u;
    }
  }
  for (const std::vector<std::uint8_t>& flags : inside)
    census.inside_vertices +=
        static_cast<std::uint64_t>(std::count(flags.begin(), flags.end(), 1u));
  return census;
}

}  // namespace deformcd
