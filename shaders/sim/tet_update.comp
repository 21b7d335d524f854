#version 430
// TetUpdate (beyond the paper): one invocation per tetrahedron with nonzero volume stiffness
// computes the volume forces on its four corners into the corners' slots (SSBO 20 names them),
// which lie node by node so that sim/node_update.comp reads each node's corners contiguously.
// Each slot belongs to one corner of one tetrahedron, so there is no write conflict.
#include "common/layout.glsl"
#include "common/exact_math.glsl"
#include "sim/mass_spring.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_TET_INFO) readonly buffer TetInfo {
  Tetra tets[];
};
layout(std430, binding = BINDING_TET_CORNER_SLOT) readonly buffer TetCornerSlots {
  uvec4 corner_slots[];
};
layout(std430, binding = BINDING_CORNER_FORCE) writeonly buffer CornerForces {
  vec4 corner_forces[];
};
layout(std430, binding = BINDING_BODY_PARAMS) readonly buffer BodyParameters {
  BodyParams body_params[];
};
layout(std430, binding = BINDING_NODE_BODY) readonly buffer NodeBody {
  uint node_body[];
};

bool frozen_node(uint n) { return body_params[node_body[n]].frozen != 0.0; }

uniform uint u_tet_count;

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= u_tet_count) return;  // the last work group reaches past the end
  const Tetra tet = tets[t];
  // A tetrahedron of frozen bodies keeps its corner forces (src/core/sim/frozen_bodies.h).
  if (frozen_node(tet.a) && frozen_node(tet.b) && frozen_node(tet.c) && frozen_node(tet.d)) return;
  vec3 f0, f1, f2, f3;
  tet_volume_forces(positions[tet.a].xyz, positions[tet.b].xyz, positions[tet.c].xyz,
                    positions[tet.d].xyz, tet.rest_volume, tet.stiffness, f0, f1, f2, f3);
  const uvec4 slot = corner_slots[t];
  corner_forces[slot.x] = vec4(f0, 0.0);
  corner_forces[slot.y] = vec4(f1, 0.0);
  corner_forces[slot.z] = vec4(f2, 0.0);
  corner_forces[slot.w] = vec4(f3, 0.0);
}
