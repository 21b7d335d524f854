#version 430
// octree-compact's BBCollision: the 64 x 64 leaf-box tests of a chunk of mesh pairs, as in
// collision/bb_collision.comp, but instead of a mask each overlapping box pair is appended to
// the box-pair list (SSBO 30) as global box indices (64 a + i, 64 b + j), at a slot taken with
// atomicAdd on counters.box_pairs (which counts every overlap, the ones past the capacity too:
// the host grows the list and reruns the pass then). Invocation (i, j, z): box i of mesh pair
// u_pair_first + z's mesh a against box j of its mesh b.
#include "collision/broad_phase.glsl"
#include "collision/counters.glsl"
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = BINDING_BOX_INFO) readonly buffer BoxInfo {
  Box boxes[];
};
layout(std430, binding = BINDING_BODY_PAIR) readonly buffer BodyPairs {
  BodyPair mesh_pairs[];
};
layout(std430, binding = BINDING_BOX_PAIR_LIST) writeonly buffer BoxPairList {
  uvec2 box_pair_list[];
};

uniform uint u_pair_first;          // the chunk's first mesh pair
uniform uint u_box_pair_capacity;   // uvec2 slots in SSBO 30

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint j = gl_GlobalInvocationID.y;
  const BodyPair pair = mesh_pairs[u_pair_first + gl_GlobalInvocationID.z];
  const uint box_a = LEAF_BOXES_PER_BODY * pair.a + i;
  const uint box_b = LEAF_BOXES_PER_BODY * pair.b + j;
  if (!boxes_overlap(boxes[box_a], boxes[box_b])) return;
  const uint slot = atomicAdd(counters.box_pairs, 1u);
  if (slot < u_box_pair_capacity) box_pair_list[slot] = uvec2(box_a, box_b);
}
