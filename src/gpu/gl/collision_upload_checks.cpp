#include "gpu/gl/collision_upload_checks.h"

#include <algorithm>
#include <string>

#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/collision_work_buffers.h"

namespace deformcd::gl {

namespace {

using collision::CollisionData;
using std::to_string;

[[noreturn]] void inconsistent(const std::string& what) {
  throw Error("CollisionData is inconsistent: " + what);
}

std::string mesh_name(const CollisionData& d, std::size_t m) {
  return m < d.mesh_names.size() ? d.mesh_names[m] : "mesh " + to_string(m);
}

// Mesh m's faces and rows lie inside the arrays.
void check_mesh(const CollisionData& d, std::uint32_t m) {
  const gpu::MeshInfo& info = d.meshes[m];
  const std::string name = mesh_name(d, m);
  if (std::uint64_t{info.face_offset} + info.face_count > d.faces.size()) {
    inconsistent(name + "'s faces [" + to_string(info.face_offset) + ", +" +
                 to_string(info.face_count) + ") reach past the " + to_string(d.faces.size()) +
                 " faces");
  }
  if (std::uint64_t{info.box_face_offset} + info.box_face_count > d.box_faces.size()) {
    inconsistent(name + "'s box-face rows [" + to_string(info.box_face_offset) + ", +" +
                 to_string(info.box_face_count) + ") reach past the " +
                 to_string(d.box_faces.size()) + " rows");
  }
}

// Each face names a mesh whose face range holds it, and vertices of that mesh: the shaders read
// vertex_position(face.body, corner) without bounds.
void check_faces(const CollisionData& d) {
  for (std::size_t f = 0; f < d.faces.size(); ++f) {
    const gpu::Face& face = d.faces[f];
    if (face.body >= d.mesh_count()) {
      inconsistent("face " + to_string(f) + " names mesh " + to_string(face.body) +
                   ", but there are " + to_string(d.mesh_count()) + " meshes");
    }
    const gpu::MeshInfo& m = d.meshes[face.body];
    if (f < m.face_offset || f - m.face_offset >= m.face_count) {
      inconsistent("face " + to_string(f) + " names " + mesh_name(d, face.body) +
                   ", whose faces are [" + to_string(m.face_offset) + ", +" +
                   to_string(m.face_count) + ")");
    }
    for (std::uint32_t v : {face.a, face.b, face.c}) {
      if (v >= m.vertex_count) {
        inconsistent("face " + to_string(f) + " has vertex " + to_string(v) + ", but " +
                     mesh_name(d, face.body) + " has " + to_string(m.vertex_count) + " vertices");
      }
    }
  }
}

// Leaf box k of mesh m (box 64 m + k: the shaders index boxes by mesh) lists rows of that mesh
// only, each naming box k and a face of the mesh whose face_boxes has bit k (the narrow phase's
// deduplication reads those bits).
void check_box_rows(const CollisionData& d, std::uint32_t m) {
  const gpu::MeshInfo& info = d.meshes[m];
  for (std::uint32_t k = 0; k < gpu::kLeafBoxesPerBody; ++k) {
    const glm::uvec2 rows = d.box_rows[gpu::kLeafBoxesPerBody * m + k];
    const std::string box = "leaf box " + to_string(k) + " of " + mesh_name(d, m);
    if (rows.x < info.box_face_offset ||
        std::uint64_t{rows.x} + rows.y >
            std::uint64_t{info.box_face_offset} + info.box_face_count) {
      inconsistent(box + " has rows [" + to_string(rows.x) + ", +" + to_string(rows.y) +
                   ") outside its mesh's [" + to_string(info.box_face_offset) + ", +" +
                   to_string(info.box_face_count) + ")");
    }
    for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
      const gpu::BoxFace& row = d.box_faces[r];
      if (row.box != k || row.face < info.face_offset ||
          row.face - info.face_offset >= info.face_count) {
        inconsistent(box + ": row " + to_string(r) + " names box " + to_string(row.box) +
                     " and face " + to_string(row.face) + ", not box " + to_string(k) +
                     " and a face of the mesh");
      }
      if (!collision::has_box(d.face_boxes[row.face], k)) {
        inconsistent(box + " lists face " + to_string(row.face) +
                     ", but the face's face_boxes lacks bit " + to_string(k));
      }
    }
  }
}

void check_mesh_pairs(const CollisionData& d) {
  for (std::size_t p = 0; p < d.mesh_pairs.size(); ++p) {
    const gpu::BodyPair pair = d.mesh_pairs[p];
    if (!(pair.a <= pair.b && pair.b < d.mesh_count())) {
      inconsistent("mesh pair " + to_string(p) + " is (" + to_string(pair.a) + ", " +
                   to_string(pair.b) + "), not a <= b < " + to_string(d.mesh_count()));
    }
  }
}

// Mesh m's tree covers nodes [root, root + 2 x faces - 1) right after the previous mesh's,
// in preorder (children after their parent, so that the refit's walks up end at the root),
// each child naming its parent, each face of the mesh in exactly one leaf, and no deeper than
// the traversal stack (the shaders' BVH_MAX_DEPTH).
void check_bvh(const CollisionData& d, std::uint32_t m, std::uint32_t root) {
  const gpu::MeshInfo& info = d.meshes[m];
  const gpu::BodyBvh& t = d.mesh_bvhs[m];
  const std::string name = mesh_name(d, m) + "'s BVH";
  if (t.root != root || t.node_count != 2 * std::uint64_t{info.face_count} - 1 ||
      std::uint64_t{root} + t.node_count > d.bvh_nodes.size()) {
    inconsistent(name + " has nodes [" + to_string(t.root) + ", +" + to_string(t.node_count) +
                 "), not [" + to_string(root) + ", +" + to_string(2 * info.face_count - 1) +
                 ") within the " + to_string(d.bvh_nodes.size()) + " nodes");
  }
  if (t.depth >= collision::kBvhMaxDepth) {
    inconsistent(name + " has depth " + to_string(t.depth) + ", more than the traversal stack's " +
                 to_string(collision::kBvhMaxDepth - 1));
  }
  std::vector<std::uint32_t> depth(t.node_count, 0);
  std::vector<bool> face_seen(info.face_count, false);
  std::uint32_t leaves = 0;
  const std::uint32_t end = root + t.node_count;
  for (std::uint32_t i = root; i < end; ++i) {
    const gpu::BvhNode& n = d.bvh_nodes[i];
    const std::string node = name + ": node " + to_string(i);
    const bool parent_ok =
        i == root ? n.parent == gpu::kBvhInternal : n.parent >= root && n.parent < i;
    if (!parent_ok) {
      inconsistent(node + " has parent " + to_string(n.parent) +
                   ", not an earlier node of the tree (or none for the root)");
    }
    if (n.face != gpu::kBvhInternal) {
      if (n.face < info.face_offset || n.face - info.face_offset >= info.face_count ||
          face_seen[n.face - info.face_offset]) {
        inconsistent(node + " is a leaf of face " + to_string(n.face) +
                     ", not a face of the mesh listed once");
      }
      face_seen[n.face - info.face_offset] = true;
      ++leaves;
      continue;
    }
    if (n.left == n.right) inconsistent(node + " has the same node as both children");
    for (std::uint32_t child : {n.left, n.right}) {
      if (child <= i || child >= end || d.bvh_nodes[child].parent != i) {
        inconsistent(node + " has child " + to_string(child) +
                     ", not a later node of the tree naming it as parent");
      }
      depth[child - root] = depth[i - root] + 1;
    }
  }
  // Every face in a leaf, 2 x faces - 1 nodes, each child claimed by the one parent it names:
  // a binary tree from the root, every node reachable.
  if (leaves != info.face_count) {
    inconsistent(name + " has " + to_string(leaves) + " leaves for " + to_string(info.face_count) +
                 " faces");
  }
  const std::uint32_t deepest = *std::max_element(depth.begin(), depth.end());
  if (deepest > t.depth) {
    inconsistent(name + " is " + to_string(deepest) + " deep, but its BodyBvh says " +
                 to_string(t.depth));
  }
}

void check_bvhs(const CollisionData& d) {
  if (d.mesh_bvhs.size() != d.mesh_count()) {
    inconsistent("mesh_bvhs has " + to_string(d.mesh_bvhs.size()) + " entries, but there are " +
                 to_string(d.mesh_count()) + " meshes");
  }
  std::uint32_t root = 0;
  for (std::uint32_t m = 0; m < d.mesh_count(); ++m) {
    if (d.meshes[m].face_count == 0) {
      inconsistent(mesh_name(d, m) + " has no faces, so no BVH");
    }
    check_bvh(d, m, root);
    root += d.mesh_bvhs[m].node_count;
  }
  if (root != d.bvh_nodes.size()) {
    inconsistent("bvh_nodes has " + to_string(d.bvh_nodes.size()) +
                 " nodes, but the meshes' trees have " + to_string(root));
  }
}

template <class T>
BufferSize size_of(std::string_view name, std::uint32_t binding, std::uint64_t count) {
  return {name, binding, count, sizeof(T)};
}

}  // namespace

std::vector<BufferSize> collision_buffer_sizes(const CollisionData& d,
                                               const CollisionCapacities& capacities) {
  const std::uint64_t meshes = d.mesh_count();
  const std::uint64_t faces = d.faces.size();
  const std::uint64_t nodes = d.bvh_nodes.size();
  constexpr std::uint64_t kMaskEntries = gpu::kLeafBoxesPerBody * gpu::kLeafBoxesPerBody;
  return {
      size_of<gpu::Box>("BoundingBox Information", gpu::kBoxInfo, gpu::kLeafBoxesPerBody * meshes),
      size_of<std::uint32_t>("BoundingBox Collision Result", gpu::kCollisionResult, faces),
      size_of<gpu::Face>("Face Information", gpu::kFaceInfo, faces),
      size_of<gpu::MeshInfo>("Mesh Information", gpu::kMeshInfo, meshes),
      size_of<gpu::BoxFace>("BoundingBox Face List", gpu::kBoxFaceList, d.box_faces.size()),
      size_of<gpu::FacePair>("Face Pair", gpu::kFacePair, capacities.face_pairs),
      size_of<std::int32_t>("BoundingBox Mask", gpu::kBoxMask,
                            capacities.mask_slots * kMaskEntries),
      size_of<glm::uvec2>("Face Boxes", gpu::kFaceBoxes, d.face_boxes.size()),
      size_of<gpu::BodyPair>("Mesh Pair", gpu::kBodyPair, d.mesh_pairs.size()),
      size_of<gpu::CollisionCounters>("Collision Counters", gpu::kCollisionCounters, 1),
      size_of<glm::uvec2>("Box Rows", gpu::kBoxRows, d.box_rows.size()),
      size_of<gpu::BvhNode>("BVH Node", gpu::kBvhNode, nodes),
      size_of<gpu::Box>("BVH Box", gpu::kBvhBox, nodes),
      size_of<gpu::BodyBvh>("Mesh BVH", gpu::kBodyBvh, d.mesh_bvhs.size()),
      size_of<glm::uvec2>("Candidate Pair", gpu::kCandidatePair, capacities.candidates),
      size_of<std::uint32_t>("Dispatch Arguments", kDispatchArgsBinding, kDispatchArgsWords),
      size_of<glm::uvec2>("Box Pair List", kBoxPairListBinding, capacities.box_pairs),
      size_of<std::uint32_t>("BVH Levels", kBvhLevelsBinding, nodes - std::min(nodes, faces)),
      size_of<gpu::BodyPair>("Touching Pairs", kTouchingPairsBinding, d.mesh_pairs.size()),
      size_of<std::uint32_t>("BVH Leaves", kBvhLeavesBinding, faces),
  };
}

void check_collision_data(const CollisionData& d) {
  for (std::uint32_t m = 0; m < d.mesh_count(); ++m)
    check_mesh(d, m);
  check_faces(d);
  check_mesh_pairs(d);
  if (!d.has_hierarchies()) inconsistent("no hierarchies (build_hierarchies first)");
  if (d.face_boxes.size() != d.faces.size()) {
    inconsistent("face_boxes has " + to_string(d.face_boxes.size()) + " entries, but faces has " +
                 to_string(d.faces.size()));
  }
  if (d.box_rows.size() != gpu::kLeafBoxesPerBody * d.mesh_count()) {
    inconsistent("box_rows has " + to_string(d.box_rows.size()) + " entries, but " +
                 to_string(d.mesh_count()) + " meshes call for " +
                 to_string(gpu::kLeafBoxesPerBody * d.mesh_count()));
  }
  for (std::uint32_t m = 0; m < d.mesh_count(); ++m)
    check_box_rows(d, m);
  check_bvhs(d);
}

}  // namespace deformcd::gl
