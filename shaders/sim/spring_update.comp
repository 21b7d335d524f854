#version 430
// SpringUpdate (the paper's compute shader 4): one invocation per spring computes the force on
// its end a from both ends' positions and velocities, its stiffness and its body's damping
// (the body of its end a).
// Each invocation writes only its own spring's slot, so there is no write conflict; the nodes
// gather these forces afterwards (sim/node_force.comp) instead of scattering them with atomics,
// which GL 4.3 lacks for floats and which would make the sum order nondeterministic.
#include "common/layout.glsl"
#include "sim/mass_spring.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) readonly buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_SPRING_INFO) readonly buffer SpringInfo {
  Spring springs[];
};
layout(std430, binding = BINDING_BODY_PARAMS) readonly buffer BodyParameters {
  BodyParams body_params[];
};
layout(std430, binding = BINDING_NODE_BODY) readonly buffer NodeBody {
  uint node_body[];
};
layout(std430, binding = BINDING_SPRING_FORCE) writeonly buffer SpringForces {
  vec4 spring_forces[];
};

uniform uint u_spring_count;

void main() {
  const uint s = gl_GlobalInvocationID.x;
  if (s >= u_spring_count) return;  // the last work group reaches past the end
  const Spring spring = springs[s];
  const BodyParams p = body_params[node_body[spring.a]];
  spring_forces[s] = vec4(
      spring_force(positions[spring.a].xyz, positions[spring.b].xyz, velocities[spring.a].xyz,
                   velocities[spring.b].xyz, spring.rest_length, spring.stiffness, p.damping),
      0.0);
}
