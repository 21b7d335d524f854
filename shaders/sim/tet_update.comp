#version 430
// TetUpdate (beyond the paper): one invocation per tetrahedron computes the volume forces on
// its four corners into its own four slots of SSBO 18; sim/node_force.comp gathers them. A
// tetrahedron with zero volume stiffness (the paper's springs-only model) is skipped: its
// slots stay zero from the upload.
#include "common/layout.glsl"
#include "sim/mass_spring.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_TET_INFO) readonly buffer TetInfo {
  Tetra tets[];
};
layout(std430, binding = BINDING_TET_FORCE) writeonly buffer TetForces {
  vec4 tet_forces[];
};

uniform uint u_tet_count;

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= u_tet_count) return;  // the last work group reaches past the end
  const Tetra tet = tets[t];
  if (tet.stiffness == 0.0) return;
  vec3 f0, f1, f2, f3;
  tet_volume_forces(positions[tet.a].xyz, positions[tet.b].xyz, positions[tet.c].xyz,
                    positions[tet.d].xyz, tet.rest_volume, tet.stiffness, f0, f1, f2, f3);
  tet_forces[4u * t] = vec4(f0, 0.0);
  tet_forces[4u * t + 1u] = vec4(f1, 0.0);
  tet_forces[4u * t + 2u] = vec4(f2, 0.0);
  tet_forces[4u * t + 3u] = vec4(f3, 0.0);
}
