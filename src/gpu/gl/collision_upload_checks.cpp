#include "collision_upload_checks.h"

#include <algorithm>
#include <string>

#include "collision_work_buffers.h"
#include "core/collision/broad_phase.h"
#include "core/collision/bvh.h"
#include "deformcd/error.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

namespace {

using std::to_string;

[[noreturn]] void inconsistent(const std::string& what) {
  throw Error("WorldState is inconsistent: " + what);
}

void check_faces(const WorldState& w) {
  for (std::size_t f = 0; f < w.faces.size(); ++f) {
    const gpu::Face& face = w.faces[f];
    for (std::uint32_t n : {face.a, face.b, face.c}) {
      if (n >= w.node_count()) {
        inconsistent("face " + to_string(f) + " has node " + to_string(n) + ", but there are " +
                     to_string(w.node_count()) + " nodes");
      }
    }
  }
}

// Object b's faces and rows lie inside the arrays, and its leaf boxes are 64 b .. 64 b + 63
// (the shaders index boxes by body, without reading box_offset).
void check_object(const WorldState& w, std::uint32_t b) {
  const gpu::ObjectInfo& o = w.objects[b];
  const std::string name = "object " + to_string(b);
  if (std::uint64_t{o.face_offset} + o.face_count > w.faces.size()) {
    inconsistent(name + "'s faces [" + to_string(o.face_offset) + ", +" + to_string(o.face_count) +
                 ") reach past the " + to_string(w.faces.size()) + " faces");
  }
  if (std::uint64_t{o.box_face_offset} + o.box_face_count > w.box_faces.size()) {
    inconsistent(name + "'s box-face rows [" + to_string(o.box_face_offset) + ", +" +
                 to_string(o.box_face_count) + ") reach past the " + to_string(w.box_faces.size()) +
                 " rows");
  }
  if (o.box_offset != gpu::kLeafBoxesPerBody * b || o.box_count != gpu::kLeafBoxesPerBody) {
    inconsistent(name + " has leaf boxes [" + to_string(o.box_offset) + ", +" +
                 to_string(o.box_count) + "), not the 64 from " +
                 to_string(gpu::kLeafBoxesPerBody * b));
  }
}

// Leaf box k of object b lists rows of that object only, each naming box k and a face of the
// object whose face_boxes has bit k (the narrow phase's deduplication reads those bits).
void check_box_rows(const WorldState& w, std::uint32_t b) {
  const gpu::ObjectInfo& o = w.objects[b];
  for (std::uint32_t k = 0; k < gpu::kLeafBoxesPerBody; ++k) {
    const glm::uvec2 rows = w.box_rows[gpu::kLeafBoxesPerBody * b + k];
    const std::string box = "leaf box " + to_string(k) + " of object " + to_string(b);
    if (rows.x < o.box_face_offset ||
        std::uint64_t{rows.x} + rows.y > std::uint64_t{o.box_face_offset} + o.box_face_count) {
      inconsistent(box + " has rows [" + to_string(rows.x) + ", +" + to_string(rows.y) +
                   ") outside its object's [" + to_string(o.box_face_offset) + ", +" +
                   to_string(o.box_face_count) + ")");
    }
    for (std::uint32_t r = rows.x; r < rows.x + rows.y; ++r) {
      const gpu::BoxFace& row = w.box_faces[r];
      if (row.box != k || row.face < o.face_offset || row.face - o.face_offset >= o.face_count) {
        inconsistent(box + ": row " + to_string(r) + " names box " + to_string(row.box) +
                     " and face " + to_string(row.face) + ", not box " + to_string(k) +
                     " and a face of the object");
      }
      if (!collision::has_box(w.face_boxes[row.face], k)) {
        inconsistent(box + " lists face " + to_string(row.face) +
                     ", but the face's face_boxes lacks bit " + to_string(k));
      }
    }
  }
}

void check_body_pairs(const WorldState& w) {
  for (std::size_t p = 0; p < w.body_pairs.size(); ++p) {
    const gpu::BodyPair pair = w.body_pairs[p];
    if (!(pair.a <= pair.b && pair.b < w.body_count())) {
      inconsistent("body pair " + to_string(p) + " is (" + to_string(pair.a) + ", " +
                   to_string(pair.b) + "), not a <= b < " + to_string(w.body_count()));
    }
  }
}

// Body b's tree covers nodes [root, root + 2 x faces - 1) right after the previous body's,
// in preorder (children after their parent, so that the refit's walks up end at the root),
// each child naming its parent, each face of the body in exactly one leaf, and no deeper than
// the traversal stack (the shaders' BVH_MAX_DEPTH).
void check_bvh(const WorldState& w, std::uint32_t b, std::uint32_t root) {
  const gpu::ObjectInfo& o = w.objects[b];
  const gpu::BodyBvh& t = w.body_bvhs[b];
  const std::string name = "body " + to_string(b) + "'s BVH";
  if (t.root != root || t.node_count != 2 * std::uint64_t{o.face_count} - 1 ||
      std::uint64_t{root} + t.node_count > w.bvh_nodes.size()) {
    inconsistent(name + " has nodes [" + to_string(t.root) + ", +" + to_string(t.node_count) +
                 "), not [" + to_string(root) + ", +" + to_string(2 * o.face_count - 1) +
                 ") within the " + to_string(w.bvh_nodes.size()) + " nodes");
  }
  if (t.depth >= collision::kBvhMaxDepth) {
    inconsistent(name + " has depth " + to_string(t.depth) + ", more than the traversal stack's " +
                 to_string(collision::kBvhMaxDepth - 1));
  }
  std::vector<std::uint32_t> depth(t.node_count, 0);
  std::vector<bool> face_seen(o.face_count, false);
  std::uint32_t leaves = 0;
  const std::uint32_t end = root + t.node_count;
  for (std::uint32_t i = root; i < end; ++i) {
    const gpu::BvhNode& n = w.bvh_nodes[i];
    const std::string node = name + ": node " + to_string(i);
    const bool parent_ok =
        i == root ? n.parent == gpu::kBvhInternal : n.parent >= root && n.parent < i;
    if (!parent_ok) {
      inconsistent(node + " has parent " + to_string(n.parent) +
                   ", not an earlier node of the tree (or none for the root)");
    }
    if (n.face != gpu::kBvhInternal) {
      if (n.face < o.face_offset || n.face - o.face_offset >= o.face_count ||
          face_seen[n.face - o.face_offset]) {
        inconsistent(node + " is a leaf of face " + to_string(n.face) +
                     ", not a face of the body listed once");
      }
      face_seen[n.face - o.face_offset] = true;
      ++leaves;
      continue;
    }
    if (n.left == n.right) inconsistent(node + " has the same node as both children");
    for (std::uint32_t child : {n.left, n.right}) {
      if (child <= i || child >= end || w.bvh_nodes[child].parent != i) {
        inconsistent(node + " has child " + to_string(child) +
                     ", not a later node of the tree naming it as parent");
      }
      depth[child - root] = depth[i - root] + 1;
    }
  }
  // Every face in a leaf, 2 x faces - 1 nodes, each child claimed by the one parent it names:
  // a binary tree from the root, every node reachable.
  if (leaves != o.face_count) {
    inconsistent(name + " has " + to_string(leaves) + " leaves for " + to_string(o.face_count) +
                 " faces");
  }
  const std::uint32_t deepest = *std::max_element(depth.begin(), depth.end());
  if (deepest > t.depth) {
    inconsistent(name + " is " + to_string(deepest) + " deep, but its BodyBvh says " +
                 to_string(t.depth));
  }
}

void check_bvhs(const WorldState& w) {
  if (w.body_bvhs.size() != w.body_count()) {
    inconsistent("body_bvhs has " + to_string(w.body_bvhs.size()) + " entries, but there are " +
                 to_string(w.body_count()) + " bodies");
  }
  std::uint32_t root = 0;
  for (std::uint32_t b = 0; b < w.body_count(); ++b) {
    check_bvh(w, b, root);
    root += w.body_bvhs[b].node_count;
  }
  if (root != w.bvh_nodes.size()) {
    inconsistent("bvh_nodes has " + to_string(w.bvh_nodes.size()) +
                 " nodes, but the bodies' trees have " + to_string(root));
  }
}

template <class T>
BufferSize size_of(std::string_view name, std::uint32_t binding, std::uint64_t count) {
  return {name, binding, count, sizeof(T)};
}

}  // namespace

std::vector<BufferSize> collision_buffer_sizes(const WorldState& w,
                                               const CollisionCapacities& capacities) {
  const std::uint64_t pair_capacity = capacities.face_pairs;
  const std::uint64_t mask_slots = capacities.mask_slots;
  constexpr std::uint64_t kMaskEntries = gpu::kLeafBoxesPerBody * gpu::kLeafBoxesPerBody;
  return {
      size_of<gpu::Box>("BoundingBox Information", gpu::kBoxInfo,
                        gpu::kLeafBoxesPerBody * w.body_count()),
      size_of<std::uint32_t>("BoundingBox Collision Result", gpu::kCollisionResult, w.faces.size()),
      size_of<gpu::Face>("Face Information", gpu::kFaceInfo, w.faces.size()),
      size_of<gpu::ObjectInfo>("Object Information", gpu::kObjectInfo, w.objects.size()),
      size_of<gpu::BoxFace>("BoundingBox Face List", gpu::kBoxFaceList, w.box_faces.size()),
      size_of<gpu::FacePair>("Face Pair", gpu::kFacePair, pair_capacity),
      size_of<std::int32_t>("BoundingBox Mask", gpu::kBoxMask, mask_slots * kMaskEntries),
      size_of<glm::uvec2>("Face Boxes", gpu::kFaceBoxes, w.face_boxes.size()),
      size_of<gpu::BodyPair>("Body Pair", gpu::kBodyPair, w.body_pairs.size()),
      size_of<gpu::CollisionCounters>("Collision Counters", gpu::kCollisionCounters, 1),
      size_of<glm::uvec2>("Box Rows", gpu::kBoxRows, w.box_rows.size()),
      size_of<gpu::BvhNode>("BVH Node", gpu::kBvhNode, w.bvh_nodes.size()),
      size_of<gpu::Box>("BVH Box", gpu::kBvhBox, w.bvh_nodes.size()),
      size_of<gpu::BodyBvh>("Body BVH", gpu::kBodyBvh, w.body_bvhs.size()),
      size_of<glm::uvec2>("Candidate Pair", gpu::kCandidatePair, capacities.candidates),
      size_of<std::uint32_t>("Dispatch Arguments", kDispatchArgsBinding, kDispatchArgsWords),
      size_of<glm::uvec2>("Box Pair List", kBoxPairListBinding, capacities.box_pairs),
      size_of<std::uint32_t>("BVH Levels", kBvhLevelsBinding,
                             w.bvh_nodes.size() - std::min(w.bvh_nodes.size(), w.faces.size())),
      size_of<gpu::BodyPair>("Touching Pairs", kTouchingPairsBinding, w.body_pairs.size()),
      size_of<std::uint32_t>("BVH Leaves", kBvhLeavesBinding, w.faces.size()),
  };
}

void check_collision_consistency(const WorldState& w) {
  if (w.face_boxes.size() != w.faces.size()) {
    inconsistent("face_boxes has " + to_string(w.face_boxes.size()) + " entries, but faces has " +
                 to_string(w.faces.size()));
  }
  if (w.box_rows.size() != gpu::kLeafBoxesPerBody * w.body_count()) {
    inconsistent("box_rows has " + to_string(w.box_rows.size()) + " entries, but " +
                 to_string(w.body_count()) + " bodies call for " +
                 to_string(gpu::kLeafBoxesPerBody * w.body_count()));
  }
  check_faces(w);
  for (std::uint32_t b = 0; b < w.body_count(); ++b) {
    check_object(w, b);
    check_box_rows(w, b);
  }
  check_body_pairs(w);
  check_bvhs(w);
}

}  // namespace deformcd::gl
