#version 430
// NodeUpdate (the paper's compute shader 3): one invocation per node integrates its velocity
// and position from the force sim/node_force.comp gathered, gravity and its body's carry
// velocity. Each invocation reads and writes only its own node.
#include "common/layout.glsl"
#include "sim/mass_spring.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_NODE_FORCE) readonly buffer NodeForces {
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
  vec4 position = positions[i];
  vec4 velocity = velocities[i];
  const vec3 carry_velocity = body_params[node_body[i]].carry_velocity.xyz;
  integrate_node(position, velocity, node_forces[i].xyz, carry_velocity,
                 SubstepConstants(u_h, u_gravity, u_velocity_decay));
  positions[i] = position;
  velocities[i] = velocity;
}
