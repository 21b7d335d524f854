#version 430
// BVH refit, one level: after collision/bvh_refit.comp wrote the leaves and the deeper levels'
// dispatches their internal nodes, one invocation per internal node of this depth (of every
// mesh) writes its box as the union of its children's. The internal nodes are listed by depth,
// deepest first (SSBO 31, built on the host); this level is entries [u_first, u_first +
// u_count). Each invocation writes only its own node; its children were written by earlier
// dispatches.
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_BVH_NODE) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(std430, binding = BINDING_BVH_BOX) buffer BvhBoxes {
  Box bvh_boxes[];
};
layout(std430, binding = BINDING_BVH_LEVELS) readonly buffer BvhLevels {
  uint bvh_levels[];  // internal nodes, deepest level first
};

uniform uint u_first;  // this level's first entry in bvh_levels
uniform uint u_count;  // its internal nodes

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;  // the last work group reaches past the end
  const uint node = bvh_levels[u_first + i];
  const BvhNode n = bvh_nodes[node];
  const Box l = bvh_boxes[n.left];
  const Box r = bvh_boxes[n.right];
  bvh_boxes[node] =
      Box(vec4(min(l.min.xyz, r.min.xyz), 0.0), vec4(max(l.max.xyz, r.max.xyz), 0.0));
}
