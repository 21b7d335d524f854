#version 430
// BVH refit, first step: one invocation per BVH node of every mesh, of which the leaves work:
// each writes its box from its face's current vertices. collision/bvh_refit_level.comp then
// fills the internal nodes level by level, deepest first. The boxes are min/max of the same
// floats as collision::refit_bvh (core/collision/bvh.cpp): bit for bit the host's boxes.
//
// Why levels rather than one dispatch in which each leaf walks up to the root (Karras 2012, an
// atomic counter per node letting the second child's walk continue; we had it): on llvmpipe
// the walks diverge within the SIMD lanes (half of them stop at each level), and the ~14 small
// level dispatches cost less than that. Measured (wall, best of 15): phase1's 17,758 nodes
// 0.7-0.9 ms against 1.0-1.6 ms; sixteen bunnies' 71,024 nodes 1.8-2.5 ms against 2.9-3.2 ms.
#include "collision/broad_phase.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_BVH_NODE) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(std430, binding = BINDING_BVH_BOX) writeonly buffer BvhBoxes {
  Box bvh_boxes[];
};

uniform uint u_node_count;  // BVH nodes of all meshes

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

void main() {
  const uint node = gl_GlobalInvocationID.x;
  if (node >= u_node_count) return;  // the last work group reaches past the end
  const uint face = bvh_nodes[node].face;
  if (face == BVH_INTERNAL) return;  // bvh_refit_level.comp's
  const Face f = faces[face];
  const uvec2 at = vertex_layout(f.body);
  Box box = empty_box();
  grow_box(box, vertex_at(at, f.a));
  grow_box(box, vertex_at(at, f.b));
  grow_box(box, vertex_at(at, f.c));
  bvh_boxes[node] = box;
}
