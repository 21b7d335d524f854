#version 430
// The proximity search's BVH refit, first step: one invocation per BVH node of every mesh, of
// which the leaves work: each writes its face's box swept over the period (its corners where
// the period starts and where their motion takes them) and grown by the face's reach, as
// CpuProximity::refit does (sweep_face's box: reach_box of swept_face_vertices, face_reaches).
// proximity/proximity_refit_level.comp then fills the internal nodes level by level, deepest
// first. The boxes are the search's own: the collision passes' (refitted on the positions
// alone) are left as they are.
#include "collision/surface.glsl"
#include "common/layout.glsl"
#include "proximity/proximity_vertices.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_BVH_NODE) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(std430, binding = BINDING_BVH_BOX) writeonly buffer BvhBoxes {
  Box bvh_boxes[];
};

uniform uint u_node_count;  // BVH nodes of all meshes

void main() {
  const uint node = gl_GlobalInvocationID.x;
  if (node >= u_node_count) return;  // the last work group reaches past the end
  const uint face = bvh_nodes[node].face;
  if (face == BVH_INTERNAL) return;  // proximity_refit_level.comp's
  const Face f = faces[face];
  vec3 x[6];
  swept_face_vertices(f, x);
  float corner[3];
  bvh_boxes[node] = reach_box6(x, face_reaches(f, corner));
}
