#include "deformcd/world_intersections.h"

#include <span>

namespace deformcd {

namespace {

// Each body's surface faces, indexed by its own nodes.
std::vector<CollisionMesh> body_surfaces(const World& world) {
  std::vector<CollisionMesh> meshes;
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    const gpu::ObjectInfo& object = world.object(b);
    CollisionMesh mesh{.vertex_count = object.node_count, .name = world.body_name(b)};
    for (std::uint32_t f = 0; f < object.face_count; ++f) {
      const gpu::Face& face = world.faces()[object.face_offset + f];
      mesh.triangles.push_back(
          {face.a - object.node_offset, face.b - object.node_offset, face.c - object.node_offset});
    }
    meshes.push_back(std::move(mesh));
  }
  return meshes;
}

}  // namespace

WorldIntersections::WorldIntersections(const World& world, int threads)
    : world_(world), counter_(body_surfaces(world), threads) {}

IntersectionCensus WorldIntersections::count() {
  positions_.resize(world_.body_count());
  std::vector<std::span<const glm::vec3>> views;
  for (std::size_t b = 0; b < world_.body_count(); ++b) {
    positions_[b] = world_.positions(b);
    views.emplace_back(positions_[b]);
  }
  return counter_.count(views);
}

}  // namespace deformcd
