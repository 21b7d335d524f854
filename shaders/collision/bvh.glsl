// BVH queries: the leaves collision::query_bvh (src/core/collision/bvh.h) finds, depth first
// with a fixed stack of BVH_MAX_DEPTH + 1 entries, which holds any tree of depth <=
// BVH_MAX_DEPTH (the host checks every mesh's depth before upload). The boxes are the refitted ones
// (collision/bvh_refit.comp).
//
// An including shader must define
//   void bvh_visit(uint face);
// (the C++ template's `visit`): called for every leaf whose box overlaps the query box.
#include "collision/broad_phase.glsl"
#include "common/layout.glsl"

layout(std430, binding = BINDING_BVH_NODE) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(std430, binding = BINDING_BVH_BOX) readonly buffer BvhBoxes {
  Box bvh_boxes[];
};

void bvh_visit(uint face);

// Calls bvh_visit(face) for every leaf of the tree at `root` whose box overlaps `query`
// (closed boxes). Children are tested before they are pushed, so that every node taken is one
// whose box overlaps, and only the right child of a node whose children both overlap waits on
// the stack (at most one per level).
void query_bvh(uint root, Box query) {
  if (!boxes_overlap(bvh_boxes[root], query)) return;
  uint stack[BVH_MAX_DEPTH + 1u];
  uint size = 0u;
  uint node = root;
  while (true) {
    const BvhNode n = bvh_nodes[node];
    bool descend = false;
    if (n.face != BVH_INTERNAL) {
      bvh_visit(n.face);
    } else {
      const bool left = boxes_overlap(bvh_boxes[n.left], query);
      const bool right = boxes_overlap(bvh_boxes[n.right], query);
      if (left && right) stack[size++] = n.right;
      descend = left || right;
      node = left ? n.left : n.right;
    }
    if (!descend) {
      if (size == 0u) return;
      node = stack[--size];
    }
  }
}
