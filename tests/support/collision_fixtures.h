#pragma once
// Collision data built in tests from bodies (their surfaces become a detector's meshes), with
// the positions held on the host the way a caller would hold them: one vec4 array per mesh.
// For tests of the collision backends below the Detector (CpuCollision, GlCollision).

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "core/collision/collision_backend.h"
#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/detector.h"
#include "deformcd/simulation_state.h"

namespace deformcd::test {

/// The surface of each body as a detector mesh (its faces' nodes are the body's node indices).
inline std::vector<CollisionMesh> surface_meshes(const std::vector<BodyInit>& bodies,
                                                 bool self_collision = false) {
  std::vector<CollisionMesh> meshes;
  for (const BodyInit& b : bodies) {
    CollisionMesh m;
    m.vertex_count = static_cast<std::uint32_t>(b.body.positions.size());
    for (const gpu::Face& f : b.body.faces)
      m.triangles.push_back({f.a, f.b, f.c});
    m.self_collision = self_collision;
    m.name = b.name;
    meshes.push_back(std::move(m));
  }
  return meshes;
}

/// Collision data of bodies with their positions, kept per mesh as vec4 (xyz, w = 1).
struct CollisionFixture {
  collision::CollisionData data;
  std::vector<std::vector<glm::vec4>> positions;  // per mesh
  std::vector<collision::MeshVertices> views;     // per mesh, into `positions`

  /// Sources pointing at `positions` (host arrays, stride 16 bytes).
  [[nodiscard]] std::vector<collision::PositionSource> host_sources() const {
    std::vector<collision::PositionSource> sources;
    for (const std::vector<glm::vec4>& p : positions) {
      collision::PositionSource s;
      s.kind = collision::PositionSource::Kind::kHost;
      s.host = &p[0].x;
      s.stride_bytes = sizeof(glm::vec4);
      s.vertex_count = static_cast<std::uint32_t>(p.size());
      sources.push_back(s);
    }
    return sources;
  }
  /// Re-points `views` after `positions` changed size.
  void refresh_views() {
    views.clear();
    for (const std::vector<glm::vec4>& p : positions)
      views.push_back({&p[0].x, 4u});
  }
  [[nodiscard]] collision::VertexPositions vertices() const { return views.data(); }
};

/// The bodies' surfaces laid out for a detector, hierarchies built on their current positions.
inline CollisionFixture collision_fixture(const std::vector<BodyInit>& bodies,
                                          bool self_collision = false) {
  CollisionFixture f;
  f.data = collision::lay_out_meshes(surface_meshes(bodies, self_collision), nullptr);
  for (const BodyInit& b : bodies)
    f.positions.push_back(b.body.positions);
  f.refresh_views();
  collision::build_hierarchies(f.data, f.vertices());
  return f;
}

}  // namespace deformcd::test
