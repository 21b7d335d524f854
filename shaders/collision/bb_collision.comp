#version 430
// BBCollision (the paper's compute shader 1, Algorithm 2): the 64 x 64 leaf-box tests of a
// chunk of mesh pairs. Invocation (i, j, z) tests box i of mesh pair u_pair_first + z's mesh a
// against box j of its mesh b and writes mask slot z's entry (i, j): 1 when they overlap, 0
// otherwise. Each invocation writes only its own entry. The host runs chunks of at most
// "mask slots" mesh pairs, so the mask takes slots x 64 x 64 ints however many meshes there are.
#include "collision/broad_phase.glsl"
#include "collision/counters.glsl"
#include "common/layout.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = BINDING_BOX_INFO) readonly buffer BoxInfo {
  Box boxes[];
};
layout(std430, binding = BINDING_BODY_PAIR) readonly buffer BodyPairs {
  BodyPair mesh_pairs[];
};
layout(std430, binding = BINDING_BOX_MASK) writeonly buffer BoxMask {
  int box_mask[];  // slot z, entry (i, j) at z * 4096 + i * 64 + j
};

uniform uint u_pair_first;  // the chunk's first mesh pair

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint j = gl_GlobalInvocationID.y;
  const uint slot = gl_GlobalInvocationID.z;
  const BodyPair pair = mesh_pairs[u_pair_first + slot];
  const uint entry = slot * LEAF_BOXES_PER_BODY * LEAF_BOXES_PER_BODY + i * LEAF_BOXES_PER_BODY + j;
  box_mask[entry] = -1;  // as in the paper: "not tested", until the test below
  const bool overlap = boxes_overlap(boxes[LEAF_BOXES_PER_BODY * pair.a + i],
                                     boxes[LEAF_BOXES_PER_BODY * pair.b + j]);
  box_mask[entry] = overlap ? 1 : 0;
  if (overlap) atomicAdd(counters.box_pairs, 1u);
}
