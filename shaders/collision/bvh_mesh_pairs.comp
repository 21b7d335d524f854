#version 430
// The bvh broad phase's mesh-pair culling, after collision/bvh_refit.comp: one invocation per
// mesh pair (SSBO 22) tests the two root boxes and appends the pair, when they overlap, to the
// touching-pair list, at a slot taken with atomicAdd on the count in the dispatch-args buffer
// (reset by the host each pass). The list holds every mesh pair, so it cannot overflow. Only
// the touching pairs then get traversal work groups (collision/bvh_traverse.comp): with many
// meshes, most pairs are apart, and a work group that only finds that out still costs a launch.
#include "collision/broad_phase.glsl"
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_BODY_PAIR) readonly buffer BodyPairs {
  BodyPair mesh_pairs[];
};
layout(std430, binding = BINDING_BODY_BVH) readonly buffer BodyBvhs {
  BodyBvh mesh_bvhs[];
};
layout(std430, binding = BINDING_BVH_BOX) readonly buffer BvhBoxes {
  Box bvh_boxes[];
};
layout(std430, binding = BINDING_DISPATCH_ARGS) buffer DispatchArgs {
  uint dispatch_args[];
};
layout(std430, binding = BINDING_TOUCHING_PAIRS) writeonly buffer TouchingPairs {
  uvec2 touching_pairs[];
};

uniform uint u_pair_count;  // mesh pairs

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

void main() {
  const uint p = gl_GlobalInvocationID.x;
  if (p >= u_pair_count) return;  // the last work group reaches past the end
  const BodyPair pair = mesh_pairs[p];
  if (!boxes_overlap(bvh_boxes[mesh_bvhs[pair.a].root], bvh_boxes[mesh_bvhs[pair.b].root])) {
    return;
  }
  const uint slot = atomicAdd(dispatch_args[DISPATCH_ARGS_TOUCHING], 1u);
  touching_pairs[slot] = uvec2(pair.a, pair.b);
}
