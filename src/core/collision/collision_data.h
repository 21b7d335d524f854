#pragma once
// What a collision backend holds for a detector: the meshes' triangles (vertex indices local to
// each mesh), the mesh pairs to test, and the hierarchies built on a pose (the paper's leaf-box
// lists, one BVH per mesh). One array per GPU buffer, as the GL backend uploads them.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "core/collision/vertex_positions.h"
#include "deformcd/collision_mesh.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

struct CollisionData {
  std::vector<gpu::Face> faces;       ///< mesh by mesh; Face::body is the mesh
  std::vector<gpu::MeshInfo> meshes;  ///< per mesh (position_* set by the GL backend)
  /// The mesh pairs to test, sorted by (a, b), a <= b ((m, m): m with itself).
  std::vector<gpu::BodyPair> mesh_pairs;
  std::vector<std::string> mesh_names;  ///< "mesh 1 ('cloth')", for messages
  // Built on a pose by build_hierarchies (empty before):
  /// The BoundingBox Face List, mesh by mesh, and within a mesh box by box (Fig. 7).
  std::vector<gpu::BoxFace> box_faces;
  std::vector<glm::uvec2> face_boxes;   ///< per face, bit k set if leaf box k lists it
  std::vector<glm::uvec2> box_rows;     ///< per leaf box, first row in box_faces, count
  std::vector<gpu::BvhNode> bvh_nodes;  ///< every mesh's BVH, mesh by mesh
  std::vector<gpu::BodyBvh> mesh_bvhs;  ///< per mesh

  [[nodiscard]] std::size_t mesh_count() const { return meshes.size(); }
  [[nodiscard]] bool has_hierarchies() const { return !mesh_bvhs.empty(); }
};

/// Checks the meshes and the pairs and lays out faces, meshes and mesh pairs. `pairs` empty:
/// every pair of different meshes, plus (m, m) for each mesh with self_collision. Throws
/// InputError naming the mesh and the triangle (index out of range), a mesh without triangles,
/// or the pair naming a mesh that does not exist.
[[nodiscard]] CollisionData lay_out_meshes(const std::vector<CollisionMesh>& meshes,
                                           const std::vector<MeshPair>* pairs);

/// Where each mesh's vertices start in the per-vertex arrays of a proximity search (every
/// mesh's vertices, mesh after mesh), then their total: mesh_count() + 1 entries.
[[nodiscard]] std::vector<std::uint32_t> vertex_firsts(const std::vector<gpu::MeshInfo>& meshes);
[[nodiscard]] std::vector<std::uint32_t> vertex_firsts(const CollisionData& data);

/// The mesh pairs a proximity search looks at (indices into data.mesh_pairs, ascending): every
/// pair but those of two meshes flagged in `still` (one flag per mesh, or none: every pair),
/// a still mesh with itself among them (meshes that do not move cannot come closer); of those,
/// the pairs of two different meshes when `between`, and a mesh with itself when `within` flags
/// it (one flag per mesh, or none: every mesh).
[[nodiscard]] std::vector<std::uint32_t> searched_mesh_pairs(
    const CollisionData& data, std::span<const std::uint8_t> still, bool between = true,
    std::span<const std::uint8_t> within = {});

/// Builds the leaf-box lists and the BVHs of every mesh on `pose`.
void build_hierarchies(CollisionData& data, VertexPositions pose);

/// "mesh 1" or "mesh 1 ('cloth')".
[[nodiscard]] std::string mesh_label(std::size_t mesh, const std::string& name);

}  // namespace deformcd::collision
