#version 430
// NodeForce and NodeUpdate (the paper's compute shaders 5 and 3) in one pass, since nothing
// reads another node's force: one invocation per node sums (k q) u over its springs' edge
// states (sim/edge_update.comp) in its list order, then its tetrahedron corners' forces
// (sim/tet_update.comp) in slot order, and integrates. A fixed order per node makes the sum
// deterministic and equal to the CPU backend's (src/cpu/cpu_simulation.cpp), bit for bit.
#include "common/layout.glsl"
#include "common/exact_math.glsl"
#include "sim/mass_spring.glsl"
// The gathers are inline: GLSL cannot pass buffers to functions.

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_EDGE_STATE) readonly buffer EdgeStates {
  vec4 edge_states[];
};
layout(std430, binding = BINDING_NODE_EDGE_OFFSET) readonly buffer NodeEdgeOffsets {
  uint node_edge_offset[];
};
layout(std430, binding = BINDING_NODE_EDGE_TERM) readonly buffer NodeEdgeTerms {
  EdgeTerm node_edge_terms[];
};
layout(std430, binding = BINDING_CORNER_FORCE) readonly buffer CornerForces {
  vec4 corner_forces[];
};
layout(std430, binding = BINDING_NODE_CORNER_OFFSET) readonly buffer NodeCornerOffsets {
  uint node_corner_offset[];
};
layout(std430, binding = BINDING_NODE_FORCE) writeonly buffer NodeForces {
  vec4 node_forces[];
};
layout(std430, binding = BINDING_BODY_PARAMS) readonly buffer BodyParameters {
  BodyParams body_params[];
};
layout(std430, binding = BINDING_NODE_BODY) readonly buffer NodeBody {
  uint node_body[];
};

uniform uint u_node_count;
uniform float u_h;
uniform vec3 u_gravity;
uniform float u_velocity_decay;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  // A frozen body's node stays as the last substep left it (src/core/sim/frozen_bodies.h).
  if (body_params[node_body[i]].frozen != 0.0) return;
  // The CPU's node pass, line for line: each spring's term (sim::spring_term), then each
  // corner, each summed from zero in list order. precise: no multiply-add may be fused, so
  // that every product is rounded as the CPU rounds it.
  // The lists' bounds are read once: a bound in the loop's condition was read again on every
  // iteration (llvmpipe's node pass took 18 % longer).
  const uint edge_begin = node_edge_offset[i], edge_end = node_edge_offset[i + 1u];
  precise vec3 springs = vec3(0.0);
  for (uint k = edge_begin; k < edge_end; ++k) {
    const EdgeTerm term = node_edge_terms[k];
    springs += spring_term(edge_states[term.edge], term.signed_stiffness);
  }
  precise vec3 tets = vec3(0.0);
  const uint corner_begin = node_corner_offset[i], corner_end = node_corner_offset[i + 1u];
  for (uint k = corner_begin; k < corner_end; ++k)
    tets += corner_forces[k].xyz;
  const vec3 force = springs + tets;
  node_forces[i] = vec4(force, 0.0);
  vec4 position = positions[i];
  vec4 velocity = velocities[i];
  const vec3 carry_velocity = body_params[node_body[i]].carry_velocity.xyz;
  integrate_node(position, velocity, force, carry_velocity,
                 SubstepConstants(u_h, u_gravity, u_velocity_decay));
  positions[i] = position;
  velocities[i] = velocity;
}
