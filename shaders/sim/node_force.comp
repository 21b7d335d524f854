#version 430
// NodeForce (the paper's compute shader 5): one invocation per node sums the forces of its
// springs, written by sim/spring_update.comp, over the node's CSR list in list order, then the
// volume forces of its tetrahedron corners (sim/tet_update.comp), likewise. A fixed
// order per node makes the sum deterministic and equal to the CPU backend's.
#include "common/layout.glsl"
// Not sim/mass_spring.glsl: GLSL cannot pass buffers to functions, so the gather is inline.

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_SPRING_FORCE) readonly buffer SpringForces {
  vec4 spring_forces[];
};
layout(std430, binding = BINDING_NODE_SPRING_OFFSET) readonly buffer NodeSpringOffsets {
  uint node_spring_offset[];
};
layout(std430, binding = BINDING_NODE_SPRING_LIST) readonly buffer NodeSpringList {
  int node_spring_list[];
};
layout(std430, binding = BINDING_TET_FORCE) readonly buffer TetForces {
  vec4 tet_forces[];
};
layout(std430, binding = BINDING_NODE_TET_OFFSET) readonly buffer NodeTetOffsets {
  uint node_tet_offset[];
};
layout(std430, binding = BINDING_NODE_TET_LIST) readonly buffer NodeTetList {
  uint node_tet_list[];
};
layout(std430, binding = BINDING_NODE_FORCE) writeonly buffer NodeForces {
  vec4 node_forces[];
};

uniform uint u_node_count;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  // gather_node_force (src/core/sim/mass_spring.h), line for line: entry +(s+1) means the
  // node is end a of spring s (force +f), -(s+1) end b (force -f).
  const uint begin = node_spring_offset[i];
  const uint end = node_spring_offset[i + 1u];
  vec3 sum = vec3(0.0);
  for (uint e = begin; e < end; ++e) {
    const int tag = node_spring_list[e];
    const vec3 f = spring_forces[(tag > 0 ? tag : -tag) - 1].xyz;
    sum += tag > 0 ? f : -f;
  }
  // gather_tet_force, line for line: the node's tetrahedron corner slots, in list order.
  const uint tet_begin = node_tet_offset[i];
  const uint tet_end = node_tet_offset[i + 1u];
  vec3 tet_sum = vec3(0.0);
  for (uint e = tet_begin; e < tet_end; ++e) tet_sum += tet_forces[node_tet_list[e]].xyz;
  node_forces[i] = vec4(sum + tet_sum, 0.0);
}
