#version 430
// Layout probe: writes a distinct value into every field of element i of each struct array, so
// that C++ reading the buffers through include/deformcd/gpu_layout.h sees exactly those values
// only if offsets, sizes and array strides agree. Field k of element i holds probe(i, k);
// tests/gl/layout_agreement_test.cpp computes the same function.
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 4) in;

layout(std430, binding = 0) buffer SpringEdges { SpringEdge edges[]; };
layout(std430, binding = 1) buffer Faces { Face faces[]; };
layout(std430, binding = 2) buffer Boxes { Box boxes[]; };
layout(std430, binding = 3) buffer BoxFaces { BoxFace box_faces[]; };
layout(std430, binding = 4) buffer ObjectInfos { ObjectInfo objects[]; };
layout(std430, binding = 5) buffer Bindings { uint bindings[]; };
layout(std430, binding = 6) buffer BodyParamsArray { BodyParams body_params[]; };
layout(std430, binding = 7) buffer Tets { Tetra tets[]; };
layout(std430, binding = 8) buffer BodyPairs { BodyPair body_pairs[]; };
layout(std430, binding = 9) buffer FacePairs { FacePair face_pairs[]; };
layout(std430, binding = 10) buffer Counters { CollisionCounters counters[]; };
layout(std430, binding = 11) buffer BvhNodes { BvhNode bvh_nodes[]; };
layout(std430, binding = 12) buffer BodyBvhs { BodyBvh body_bvhs[]; };
layout(std430, binding = 13) buffer MeshInfos { MeshInfo meshes[]; };
layout(std430, binding = 14) buffer ContactPairs { ContactPair contact_pairs[]; };
layout(std430, binding = 15) buffer EdgeTerms { EdgeTerm edge_terms[]; };

uniform uint u_count;

uint probe(uint i, uint k) { return 1000u * (i + 1u) + k; }
float probef(uint i, uint k) { return float(probe(i, k)); }
vec4 probe4(uint i, uint k) {
  return vec4(probef(i, k), probef(i, k + 1u), probef(i, k + 2u), probef(i, k + 3u));
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;

  edges[i].a = probe(i, 0u);
  edges[i].b = probe(i, 1u);
  edges[i].rest_length = probef(i, 2u);
  edges[i].damping = probef(i, 3u);

  edge_terms[i].edge = probe(i, 0u);
  edge_terms[i].signed_stiffness = probef(i, 1u);

  faces[i].a = probe(i, 0u);
  faces[i].b = probe(i, 1u);
  faces[i].c = probe(i, 2u);
  faces[i].body = probe(i, 3u);

  boxes[i].min = probe4(i, 0u);
  boxes[i].max = probe4(i, 4u);

  box_faces[i].face = probe(i, 0u);
  box_faces[i].box = probe(i, 1u);

  objects[i].node_offset = probe(i, 0u);
  objects[i].node_count = probe(i, 1u);
  objects[i].face_offset = probe(i, 2u);
  objects[i].face_count = probe(i, 3u);
  objects[i].spring_offset = probe(i, 4u);
  objects[i].spring_count = probe(i, 5u);
  objects[i].tet_offset = probe(i, 6u);
  objects[i].tet_count = probe(i, 7u);
  objects[i].box_offset = probe(i, 8u);
  objects[i].box_count = probe(i, 9u);
  objects[i].box_face_offset = probe(i, 10u);
  objects[i].box_face_count = probe(i, 11u);

  body_params[i].carry_velocity = probe4(i, 0u);
  body_params[i].damping = probef(i, 4u);
  body_params[i].frozen = probef(i, 5u);
  body_params[i].pad1 = probef(i, 6u);
  body_params[i].pad2 = probef(i, 7u);

  tets[i].a = probe(i, 0u);
  tets[i].b = probe(i, 1u);
  tets[i].c = probe(i, 2u);
  tets[i].d = probe(i, 3u);
  tets[i].rest_volume = probef(i, 4u);
  tets[i].stiffness = probef(i, 5u);
  tets[i].pad0 = probef(i, 6u);
  tets[i].pad1 = probef(i, 7u);

  body_pairs[i].a = probe(i, 0u);
  body_pairs[i].b = probe(i, 1u);

  face_pairs[i].face_a = probe(i, 0u);
  face_pairs[i].face_b = probe(i, 1u);
  face_pairs[i].coplanar = probe(i, 2u);
  face_pairs[i].pad = probe(i, 3u);
  face_pairs[i].segment0 = probe4(i, 4u);
  face_pairs[i].segment1 = probe4(i, 8u);

  counters[i].face_pairs = probe(i, 0u);
  counters[i].box_pairs = probe(i, 1u);
  counters[i].colliding_faces = probe(i, 2u);
  counters[i].candidates = probe(i, 3u);

  bvh_nodes[i].left = probe(i, 0u);
  bvh_nodes[i].right = probe(i, 1u);
  bvh_nodes[i].parent = probe(i, 2u);
  bvh_nodes[i].face = probe(i, 3u);

  body_bvhs[i].root = probe(i, 0u);
  body_bvhs[i].node_count = probe(i, 1u);
  body_bvhs[i].depth = probe(i, 2u);
  body_bvhs[i].pad = probe(i, 3u);

  meshes[i].vertex_count = probe(i, 0u);
  meshes[i].face_offset = probe(i, 1u);
  meshes[i].face_count = probe(i, 2u);
  meshes[i].box_face_offset = probe(i, 3u);
  meshes[i].box_face_count = probe(i, 4u);
  meshes[i].position_offset = probe(i, 5u);
  meshes[i].position_stride = probe(i, 6u);
  meshes[i].pad = probe(i, 7u);

  contact_pairs[i].nodes = uvec4(probe(i, 0u), probe(i, 1u), probe(i, 2u), probe(i, 3u));
  contact_pairs[i].kind = probe(i, 4u);
  contact_pairs[i].thickness = probef(i, 5u);
  contact_pairs[i].gap = probef(i, 6u);
  contact_pairs[i].closing_speed = probef(i, 7u);
  contact_pairs[i].side = probef(i, 8u);
  contact_pairs[i].step_limit = probef(i, 9u);
  contact_pairs[i].converge = probef(i, 10u);
  contact_pairs[i].hold_depth = probef(i, 11u);

  if (i == 0u) {
    bindings[0] = BINDING_NODE_POSITION;
    bindings[1] = BINDING_NODE_VELOCITY;
    bindings[2] = BINDING_SPRING_EDGE;
    bindings[3] = BINDING_NODE_FORCE;
    bindings[4] = BINDING_BOX_INFO;
    bindings[5] = BINDING_COLLISION_RESULT;
    bindings[6] = BINDING_FACE_NORMAL;
    bindings[7] = BINDING_FACE_INFO;
    bindings[8] = BINDING_OBJECT_INFO;
    bindings[9] = BINDING_BOX_FACE_LIST;
    bindings[10] = BINDING_FACE_PAIR;
    bindings[11] = BINDING_BOX_MASK;
    bindings[12] = BINDING_BODY_PARAMS;
    bindings[13] = BINDING_NODE_BODY;
    bindings[14] = BINDING_EDGE_STATE;
    bindings[15] = BINDING_NODE_EDGE_OFFSET;
    bindings[16] = BINDING_NODE_EDGE_TERM;
    bindings[17] = BINDING_TET_INFO;
    bindings[18] = BINDING_CORNER_FORCE;
    bindings[19] = BINDING_NODE_CORNER_OFFSET;
    bindings[20] = BINDING_TET_CORNER_SLOT;
    bindings[21] = BINDING_FACE_BOXES;
    bindings[22] = BINDING_BODY_PAIR;
    bindings[23] = BINDING_COLLISION_COUNTERS;
    bindings[24] = BINDING_BOX_ROWS;
    bindings[25] = BINDING_BVH_NODE;
    bindings[26] = BINDING_BVH_BOX;
    bindings[27] = BINDING_BODY_BVH;
    bindings[28] = BINDING_CANDIDATE_PAIR;
    bindings[29] = BINDING_CONTACT_PAIR;
    bindings[30] = BINDING_CONTACT_SLIDES;
    bindings[31] = BINDING_NODE_CONTACT_OFFSET;
    bindings[32] = BINDING_NODE_CONTACT_LIST;
    bindings[33] = BINDING_NODE_CONTACT_COUNT;
    bindings[34] = BINDING_FRAME_START;
    bindings[35] = BINDING_NODE_MOTION;
    bindings[36] = BINDING_PROJECTION_START;
    bindings[37] = BINDING_CONTACT_IMPULSE;
    bindings[38] = BINDING_NODE_SLID;
    bindings[39] = BINDING_NODE_GUARD;
    // Not gpu::Binding: the shared constants, then the GL backend's private work buffers.
    bindings[40] = LEAF_BOXES_PER_BODY;
    bindings[41] = BVH_INTERNAL;
    bindings[42] = BVH_MAX_DEPTH;
    bindings[43] = BINDING_DISPATCH_ARGS;
    bindings[44] = BINDING_BOX_PAIR_LIST;
    bindings[45] = BINDING_BVH_LEVELS;
    bindings[46] = BINDING_TOUCHING_PAIRS;
    bindings[47] = DISPATCH_ARGS_EXPAND;
    bindings[48] = DISPATCH_ARGS_TOUCHING;
    bindings[49] = DISPATCH_ARGS_NARROW;
    bindings[50] = DISPATCH_ARGS_TRAVERSE;
    bindings[51] = BINDING_BVH_LEAVES;
    bindings[52] = BINDING_MESH_INFO;
    bindings[53] = BINDING_NON_FINITE;
    bindings[54] = CONTACT_VERTEX_FACE;
    bindings[55] = CONTACT_EDGE_EDGE;
    bindings[56] = CONTACT_UNTANGLE;
    bindings[57] = CONTACT_VOLUME;
    bindings[58] = BINDING_CONTACT_ACTING;
    bindings[59] = BINDING_ACTING_LIST;
    bindings[60] = BINDING_NODE_ACTIVE_SLOT;
    bindings[61] = BINDING_TOUCHED_NODE;
    bindings[62] = BINDING_RESPONSE_STATE;
    bindings[63] = RESPONSE_ACTING_CONTACTS;
    bindings[64] = RESPONSE_ACTING_TOTAL;
    bindings[65] = RESPONSE_TOUCHED_NODES;
    bindings[66] = RESPONSE_STRAY_FLAG;
    bindings[67] = RESPONSE_RESIDUAL_FLAG;
    bindings[68] = RESPONSE_RESIDUAL_ARGS;
    bindings[69] = RESPONSE_SLIDE_PASS_ARGS;
    bindings[70] = BINDING_SWEEP_ORDER;
    bindings[71] = BINDING_SWEEP_COLOURS;
  }
}
