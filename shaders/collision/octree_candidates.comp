#version 430
// octree-compact's candidate expansion, after collision/bb_pair_list.comp listed the
// overlapping leaf-box pairs: the face pairs the paper's N' x M' dispatch would test
// (collision/tri_tri_octree.comp), without launching the N' x M' invocations. Work group
// (x, p) takes box pair p of the list (grid-stride over the list when it outnumbers the
// dispatch) and rows 64 x .. 64 x + 63 of its box i's BoundingBox Face List (SSBO 9):
// invocation row r loops over the rows of box j and appends each face pair
// (collision/candidate_pairs.glsl) whose box pair is the first overlapping one listing both
// faces (is_first_box_pair, as the octree), so that each face pair is tested once. The lanes of
// a work group read the same row of box j at each step. The rows run along x because llvmpipe
// packs invocations into SIMD lanes along x: a work group of 1 x 64 would fill one lane in 8.
// Dispatched indirectly (collision/dispatch_args.comp): x over the largest row count of any
// leaf box, y over the list.
#include "collision/broad_phase.glsl"
#include "collision/candidate_pairs.glsl"
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(std430, binding = BINDING_BOX_INFO) readonly buffer BoxInfo {
  Box boxes[];
};
layout(std430, binding = BINDING_BOX_FACE_LIST) readonly buffer BoxFaceList {
  BoxFace box_faces[];
};
layout(std430, binding = BINDING_FACE_BOXES) readonly buffer FaceBoxes {
  uvec2 face_boxes[];  // per face: bit k set when leaf box k lists it
};
layout(std430, binding = BINDING_BOX_ROWS) readonly buffer BoxRows {
  uvec2 box_rows[];  // per leaf box: first row in box_faces, row count
};
layout(std430, binding = BINDING_BOX_PAIR_LIST) readonly buffer BoxPairList {
  uvec2 box_pair_list[];  // global leaf-box indices (64 a + i, 64 b + j)
};

uniform uint u_box_pair_capacity;  // uvec2 slots in SSBO 30

uint g_mesh_a;  // the meshes of the box pair being expanded
uint g_mesh_b;

// The octree's mask, recomputed: the mask entry (i, j) is exactly this test of the same boxes.
// mask_slot is unused: the mesh pair is the current box pair's.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) {
  return boxes_overlap(boxes[LEAF_BOXES_PER_BODY * g_mesh_a + box_a],
                       boxes[LEAF_BOXES_PER_BODY * g_mesh_b + box_b]);
}

void main() {
  const uint count = min(counters.box_pairs, u_box_pair_capacity);
  const uint r = gl_GlobalInvocationID.x;
  for (uint p = gl_WorkGroupID.y; p < count; p += gl_NumWorkGroups.y) {
    const uvec2 pair = box_pair_list[p];
    const uvec2 rows_i = box_rows[pair.x];
    if (r >= rows_i.y) continue;
    const uvec2 rows_j = box_rows[pair.y];
    g_mesh_a = pair.x / LEAF_BOXES_PER_BODY;
    g_mesh_b = pair.y / LEAF_BOXES_PER_BODY;
    const uint box_i = pair.x % LEAF_BOXES_PER_BODY;
    const uint box_j = pair.y % LEAF_BOXES_PER_BODY;
    const uint face_a = box_faces[rows_i.x + r].face;
    const uvec2 boxes_a = face_boxes[face_a];
    for (uint s = rows_j.x; s < rows_j.x + rows_j.y; ++s) {
      const uint face_b = box_faces[s].face;
      if (is_first_box_pair(boxes_a, face_boxes[face_b], box_i, box_j, 0u)) {
        append_candidate(face_a, face_b);
      }
    }
  }
}
