#version 430
// BBUpdate (the paper's compute shader 0, Algorithm 1): one invocation per leaf box, over the
// leaf boxes of all meshes (box k of mesh m is box 64 m + k), recomputes the box from the
// current vertices of the faces the pre-processing listed under it (SSBOs 24, 9), so that the
// boxes follow the deformation. A box listing no face stays empty and overlaps nothing.
// Each invocation writes only its own box. Work groups of 4, as in the paper.
#include "collision/broad_phase.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"

layout(local_size_x = 4) in;

layout(std430, binding = BINDING_BOX_FACE_LIST) readonly buffer BoxFaceList {
  BoxFace box_faces[];
};
layout(std430, binding = BINDING_BOX_ROWS) readonly buffer BoxRows {
  uvec2 box_rows[];  // per leaf box: first row in box_faces, row count
};
layout(std430, binding = BINDING_BOX_INFO) writeonly buffer BoxInfo {
  Box boxes[];
};

uniform uint u_box_count;  // 64 x meshes

// broad_phase.glsl declares it for is_first_box_pair, which this shader does not call.
bool mask_says_overlap(uint mask_slot, uint box_a, uint box_b) { return false; }

void main() {
  const uint box_id = gl_GlobalInvocationID.x;
  if (box_id >= u_box_count) return;  // the last work group reaches past the end
  const uvec2 rows = box_rows[box_id];
  // Every face a box lists is of the box's mesh.
  const uvec2 at = vertex_layout(box_id / LEAF_BOXES_PER_BODY);
  Box box = empty_box();
  for (uint r = rows.x; r < rows.x + rows.y; ++r) {
    const Face f = faces[box_faces[r].face];
    grow_box(box, vertex_at(at, f.a));
    grow_box(box, vertex_at(at, f.b));
    grow_box(box, vertex_at(at, f.c));
  }
  boxes[box_id] = box;
}
