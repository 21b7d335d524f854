#pragma once
// Meshes and host references for the GL collision tests: bodies that cross at general angles
// (their surfaces become a detector's meshes, test::collision_fixture), the all-face-pairs
// oracle (the C++ narrow phase on every pair of faces of each mesh pair), the leaf boxes and
// face boxes recomputed on the host.

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/broad_phase.h"
#include "core/collision/collision_data.h"
#include "core/collision/face_pair_intersection.h"
#include "core/collision/tri_tri_intersection.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/body.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/simulation_state.h"
#include "gl/sim_test_worlds.h"
#include "support/collision_fixtures.h"
#include "support/world_fixtures.h"

namespace deformcd::test {

/// A 3 x 3 x 3 tetrahedral grid of 0.1 m cubes, its nodes jittered by up to 0.01 m (salt picks
/// the jitter), rotated by `angle` radians about `axis` around its centre, then moved by
/// `offset`. Rotated grids cross each other's faces at general angles rather than in shared
/// planes.
inline BodyInit crossing_grid(std::uint32_t salt, double angle, glm::dvec3 axis,
                              glm::dvec3 offset) {
  TetMesh mesh = tet_grid(3, 3, 3, 0.1);
  const glm::dquat rotation = glm::angleAxis(angle, glm::normalize(axis));
  const glm::dvec3 centre(0.15);
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    const auto n = static_cast<std::uint32_t>(i);
    const glm::dvec3 jitter(hash_unit(n, salt), hash_unit(n, salt + 1), hash_unit(n, salt + 2));
    mesh.nodes[i] = centre + rotation * (mesh.nodes[i] + 0.01 * jitter - centre) + offset;
  }
  BodyInit init;
  init.body = build_body(mesh);
  init.name = "grid " + std::to_string(salt);
  return init;
}

/// Two grids whose surfaces cross (B is A's size, turned and shifted by about half a grid).
inline std::vector<BodyInit> two_crossing_grids() {
  return {crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0}),
          crossing_grid(7, 0.5, {1, 2, 3}, {0.16, 0.12, 0.09})};
}

/// The same two grids, 1 m apart.
inline std::vector<BodyInit> two_separate_grids() {
  return {crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0}),
          crossing_grid(7, 0.5, {1, 2, 3}, {1.16, 0.12, 0.09})};
}

/// Three grids, each crossing both others.
inline std::vector<BodyInit> three_crossing_grids() {
  return {crossing_grid(1, 0.0, {0, 0, 1}, {0, 0, 0}),
          crossing_grid(7, 0.5, {1, 2, 3}, {0.16, 0.12, 0.09}),
          crossing_grid(13, 0.9, {-2, 1, 1}, {0.08, 0.17, -0.1})};
}

/// Every vertex moved by up to `amount` (deterministic noise): a gentle deformation.
inline void jiggle(CollisionFixture& f, float amount, std::uint32_t salt) {
  for (std::size_t m = 0; m < f.positions.size(); ++m) {
    for (std::size_t i = 0; i < f.positions[m].size(); ++i) {
      const auto n = static_cast<std::uint32_t>(1000 * m + i);
      f.positions[m][i] += amount * glm::vec4(hash_unit(n, salt), hash_unit(n, salt + 1),
                                              hash_unit(n, salt + 2), 0.0f);
    }
  }
}

/// Sorted by (face_a, face_b), the order of all_pairs_on_host.
inline std::vector<gpu::FacePair> sorted(std::vector<gpu::FacePair> pairs) {
  std::sort(pairs.begin(), pairs.end(), [](const gpu::FacePair& x, const gpu::FacePair& y) {
    return std::tie(x.face_a, x.face_b) < std::tie(y.face_a, y.face_b);
  });
  return pairs;
}

/// The intersecting faces of every mesh pair, testing every pair of their faces, face_a from the
/// lower mesh, sorted by (face_a, face_b): tri_tri_intersect for faces of different meshes (they
/// share no vertex), face_pair_intersect with face_a < face_b for a mesh with itself.
inline std::vector<gpu::FacePair> all_pairs_on_host(const collision::CollisionData& d,
                                                    collision::VertexPositions positions) {
  std::vector<gpu::FacePair> found;
  for (const gpu::BodyPair& pair : d.mesh_pairs) {
    const gpu::MeshInfo& a = d.meshes[pair.a];
    const gpu::MeshInfo& b = d.meshes[pair.b];
    for (std::uint32_t fa = a.face_offset; fa < a.face_offset + a.face_count; ++fa) {
      glm::vec3 p[3];
      collision::face_vertices(positions, d.faces[fa], p);
      for (std::uint32_t fb = b.face_offset; fb < b.face_offset + b.face_count; ++fb) {
        if (pair.a == pair.b && fb <= fa) continue;
        glm::vec3 q[3];
        collision::face_vertices(positions, d.faces[fb], q);
        const collision::TriTriResult r =
            pair.a == pair.b ? collision::face_pair_intersect(d.faces[fa], d.faces[fb], positions)
                             : collision::tri_tri_intersect(p, q);
        if (!r.intersect) continue;
        found.push_back({fa, fb, r.coplanar ? 1u : 0u, 0u, glm::vec4(r.segment[0], 0.0f),
                         glm::vec4(r.segment[1], 0.0f)});
      }
    }
  }
  return sorted(found);
}

inline std::vector<gpu::FacePair> all_pairs_on_host(const CollisionFixture& f) {
  return all_pairs_on_host(f.data, f.vertices());
}

/// The leaf boxes at `positions`: each grown from the vertices of the faces its rows list.
inline std::vector<gpu::Box> leaf_boxes_on_host(const collision::CollisionData& d,
                                                collision::VertexPositions positions) {
  std::vector<gpu::Box> boxes;
  for (const glm::uvec2& rows : d.box_rows) {
    gpu::Box box = collision::empty_box();
    for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
      glm::vec3 t[3];
      collision::face_vertices(positions, d.faces[d.box_faces[r].face], t);
      for (const glm::vec3& v : t)
        collision::grow_box(box, v);
    }
    boxes.push_back(box);
  }
  return boxes;
}

/// Overlapping leaf-box pairs over all mesh pairs (what the octree pass counts).
inline std::uint32_t overlapping_box_pairs(const collision::CollisionData& d,
                                           const std::vector<gpu::Box>& boxes) {
  std::uint32_t count = 0;
  for (const gpu::BodyPair& pair : d.mesh_pairs) {
    for (std::uint32_t i = 0; i < gpu::kLeafBoxesPerBody; ++i) {
      for (std::uint32_t j = 0; j < gpu::kLeafBoxesPerBody; ++j) {
        count += collision::boxes_overlap(boxes[gpu::kLeafBoxesPerBody * pair.a + i],
                                          boxes[gpu::kLeafBoxesPerBody * pair.b + j])
                     ? 1u
                     : 0u;
      }
    }
  }
  return count;
}

}  // namespace deformcd::test
