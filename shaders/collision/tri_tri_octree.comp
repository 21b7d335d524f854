#version 430
// Triangle-Triangle Intersection (the paper's compute shader 2, Algorithm 3) for a chunk of
// mesh pairs, after bb_collision.comp filled their box masks. Invocation (x, y, z) takes row x
// of the BoundingBox Face List of mesh pair u_pair_first + z's mesh a and row y of its mesh
// b's (SSBO 9): N' x M' rows per pair, a face being listed under every leaf box it touches.
// It returns early unless the rows' boxes overlap (mask slot z), and unless this box pair is
// the first overlapping one listing both faces, so that each face pair is tested and reported
// once however many boxes list its faces (see broad_phase.h). The host dispatches the chunk's
// largest N' x M'; invocations past a pair's own rows return.
#include "collision/broad_phase.glsl"
#include "collision/narrow_phase.glsl"
#include "collision/meshes.glsl"
#include "common/layout.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = BINDING_BOX_FACE_LIST) readonly buffer BoxFaceList {
  BoxFace box_faces[];
};
layout(std430, binding = BINDING_FACE_BOXES) readonly buffer FaceBoxes {
  uvec2 face_boxes[];  // per face: bit k set when leaf box k lists it
};
layout(std430, binding = BINDING_BODY_PAIR) readonly buffer BodyPairs {
  BodyPair mesh_pairs[];
};
layout(std430, binding = BINDING_BOX_MASK) readonly buffer BoxMask {
  int box_mask[];  // slot z, entry (i, j) at z * 4096 + i * 64 + j
};

uniform uint u_pair_first;  // the chunk's first mesh pair

bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) {
  return box_mask[mask_slot * LEAF_BOXES_PER_BODY * LEAF_BOXES_PER_BODY +
                  box_a * LEAF_BOXES_PER_BODY + box_b] == 1;
}

void main() {
  const uint x = gl_GlobalInvocationID.x;
  const uint y = gl_GlobalInvocationID.y;
  const uint slot = gl_GlobalInvocationID.z;
  const BodyPair pair = mesh_pairs[u_pair_first + slot];
  const MeshInfo a = meshes[pair.a];
  const MeshInfo b = meshes[pair.b];
  if (x >= a.box_face_count || y >= b.box_face_count) return;
  const BoxFace row_a = box_faces[a.box_face_offset + x];
  const BoxFace row_b = box_faces[b.box_face_offset + y];
  if (row_a.face >= row_b.face) return;  // one order of a mesh's own pairs (self-collision)
  if (!mask_says_overlap(slot, row_a.box, row_b.box)) return;
  if (!is_first_box_pair(face_boxes[row_a.face], face_boxes[row_b.face], row_a.box, row_b.box,
                         slot)) {
    return;
  }
  atomicAdd(counters.candidates, 1u);  // the pairs tested, as the other broad phases count them
  test_face_pair(row_a.face, row_b.face);
}
