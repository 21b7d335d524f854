#version 430
// The proximity search's BVH refit, one level: after proximity_refit.comp wrote the leaves and
// the deeper levels' dispatches their internal nodes, one invocation per internal node of this
// depth (of every mesh) writes its box as the union of its children's, with glm's min / max as
// CpuProximity::refit takes it. The internal nodes are listed by depth, deepest first (the
// collision passes' list, bvh_work_order.h); this level is entries [u_first, u_first +
// u_count). Each invocation writes only its own node; its children were written by earlier
// dispatches.
#include "common/layout.glsl"
#include "proximity/proximity_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_BVH_NODE) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(std430, binding = BINDING_BVH_BOX) buffer BvhBoxes {
  Box bvh_boxes[];
};
layout(std430, binding = BINDING_PROXIMITY_LEVELS) readonly buffer BvhLevels {
  uint bvh_levels[];  // internal nodes, deepest level first
};

uniform uint u_first;  // this level's first entry in bvh_levels
uniform uint u_count;  // its internal nodes

// glm::min / glm::max on vec4 (b < a ? b : a, a < b ? b : a, per component).
vec4 level_min(vec4 a, vec4 b) {
  return vec4(b.x < a.x ? b.x : a.x, b.y < a.y ? b.y : a.y, b.z < a.z ? b.z : a.z,
              b.w < a.w ? b.w : a.w);
}
vec4 level_max(vec4 a, vec4 b) {
  return vec4(a.x < b.x ? b.x : a.x, a.y < b.y ? b.y : a.y, a.z < b.z ? b.z : a.z,
              a.w < b.w ? b.w : a.w);
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;  // the last work group reaches past the end
  const uint node = bvh_levels[u_first + i];
  const BvhNode n = bvh_nodes[node];
  const Box l = bvh_boxes[n.left];
  const Box r = bvh_boxes[n.right];
  bvh_boxes[node] = Box(level_min(l.min, r.min), level_max(l.max, r.max));
}
