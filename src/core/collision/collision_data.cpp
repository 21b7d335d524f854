#include "core/collision/collision_data.h"

#include <algorithm>
#include <tuple>

#include "core/collision/bvh.h"
#include "core/collision/leaf_boxes.h"
#include "deformcd/error.h"

namespace deformcd::collision {

namespace {

std::vector<gpu::BodyPair> pairs_to_test(const std::vector<CollisionMesh>& meshes,
                                         const std::vector<MeshPair>* listed) {
  const auto count = static_cast<std::uint32_t>(meshes.size());
  std::vector<gpu::BodyPair> pairs;
  for (std::uint32_t m = 0; m < count; ++m) {
    if (meshes[m].self_collision) pairs.push_back({m, m});
  }
  if (listed == nullptr) {
    for (std::uint32_t a = 0; a < count; ++a) {
      for (std::uint32_t b = a + 1; b < count; ++b)
        pairs.push_back({a, b});
    }
  } else {
    for (std::size_t i = 0; i < listed->size(); ++i) {
      const MeshPair& p = (*listed)[i];
      if (p.a >= count || p.b >= count) {
        throw InputError("mesh pairs", "pair " + std::to_string(i) + " (" + std::to_string(p.a) +
                                           ", " + std::to_string(p.b) +
                                           ") names a mesh that does not exist (there are " +
                                           std::to_string(count) + " meshes)");
      }
      pairs.push_back({std::min(p.a, p.b), std::max(p.a, p.b)});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const gpu::BodyPair& x, const gpu::BodyPair& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  pairs.erase(std::unique(pairs.begin(), pairs.end(),
                          [](const gpu::BodyPair& x, const gpu::BodyPair& y) {
                            return x.a == y.a && x.b == y.b;
                          }),
              pairs.end());
  return pairs;
}

}  // namespace

std::string mesh_label(std::size_t mesh, const std::string& name) {
  std::string label = "mesh " + std::to_string(mesh);
  if (!name.empty()) label += " ('" + name + "')";
  return label;
}

CollisionData lay_out_meshes(const std::vector<CollisionMesh>& meshes,
                             const std::vector<MeshPair>* pairs) {
  if (meshes.empty()) throw InputError("meshes", "a detector needs at least one mesh");
  CollisionData data;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const CollisionMesh& mesh = meshes[m];
    const std::string label = mesh_label(m, mesh.name);
    if (mesh.triangles.empty()) throw InputError(label, "has no triangles");
    if (mesh.triangles.size() > 0x7FFFFFFFu - data.faces.size()) {
      throw InputError(label, "too many triangles (2^31 at most over every mesh)");
    }
    gpu::MeshInfo info{};
    info.vertex_count = mesh.vertex_count;
    info.face_offset = static_cast<std::uint32_t>(data.faces.size());
    info.face_count = static_cast<std::uint32_t>(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Triangle& tri = mesh.triangles[t];
      for (std::uint32_t v : tri) {
        if (v >= mesh.vertex_count) {
          throw InputError(label, "triangle " + std::to_string(t) + " (" + std::to_string(tri[0]) +
                                      ", " + std::to_string(tri[1]) + ", " +
                                      std::to_string(tri[2]) + ") has vertex index " +
                                      std::to_string(v) + ", out of range (the mesh has " +
                                      std::to_string(mesh.vertex_count) + " vertices)");
        }
      }
      data.faces.push_back({tri[0], tri[1], tri[2], static_cast<std::uint32_t>(m)});
    }
    data.meshes.push_back(info);
    data.mesh_names.push_back(label);
  }
  data.mesh_pairs = pairs_to_test(meshes, pairs);
  return data;
}

void build_hierarchies(CollisionData& data, VertexPositions pose) {
  data.box_faces.clear();
  data.face_boxes.clear();
  data.box_rows.clear();
  data.bvh_nodes.clear();
  data.mesh_bvhs.clear();
  for (gpu::MeshInfo& m : data.meshes) {
    const LeafBoxLists lists =
        build_leaf_box_lists(pose, data.faces.data() + m.face_offset, m.face_count, m.face_offset);
    m.box_face_offset = static_cast<std::uint32_t>(data.box_faces.size());
    m.box_face_count = static_cast<std::uint32_t>(lists.rows.size());
    std::uint32_t row = m.box_face_offset;
    for (std::uint32_t box = 0; box < gpu::kLeafBoxesPerBody; ++box) {
      std::uint32_t count = 0;
      while (row + count - m.box_face_offset < lists.rows.size() &&
             lists.rows[row + count - m.box_face_offset].box == box)
        ++count;
      data.box_rows.emplace_back(row, count);
      row += count;
    }
    data.box_faces.insert(data.box_faces.end(), lists.rows.begin(), lists.rows.end());
    data.face_boxes.insert(data.face_boxes.end(), lists.face_boxes.begin(), lists.face_boxes.end());

    const auto offset = static_cast<std::uint32_t>(data.bvh_nodes.size());
    const std::vector<gpu::BvhNode> nodes =
        build_bvh(pose, data.faces, m.face_offset, m.face_count, offset);
    const std::uint32_t depth = bvh_depth(nodes, offset);
    if (depth >= kBvhMaxDepth) throw Error("BVH deeper than the traversal stack");
    data.mesh_bvhs.push_back({offset, static_cast<std::uint32_t>(nodes.size()), depth, 0u});
    data.bvh_nodes.insert(data.bvh_nodes.end(), nodes.begin(), nodes.end());
  }
}

std::vector<std::uint32_t> vertex_firsts(const std::vector<gpu::MeshInfo>& meshes) {
  std::vector<std::uint32_t> first(meshes.size() + 1u, 0u);
  for (std::size_t m = 0; m < meshes.size(); ++m)
    first[m + 1u] = first[m] + meshes[m].vertex_count;
  return first;
}

std::vector<std::uint32_t> vertex_firsts(const CollisionData& data) {
  return vertex_firsts(data.meshes);
}

std::vector<std::uint32_t> searched_mesh_pairs(const CollisionData& data,
                                               std::span<const std::uint8_t> still, bool between,
                                               std::span<const std::uint8_t> within) {
  std::vector<std::uint32_t> searched;
  searched.reserve(data.mesh_pairs.size());
  for (std::uint32_t p = 0; p < data.mesh_pairs.size(); ++p) {
    const gpu::BodyPair& pair = data.mesh_pairs[p];
    if (pair.a == pair.b ? !within.empty() && within[pair.a] == 0u : !between) continue;
    if (still.empty() || still[pair.a] == 0u || still[pair.b] == 0u) searched.push_back(p);
  }
  return searched;
}

}  // namespace deformcd::collision
