#version 430
// EdgeUpdate (the paper's compute shader 4, SpringUpdate, once per spring edge): one invocation
// per distinct spring edge computes its state (u, q), shared by every spring on it (the lion's
// 108,870 springs lie on 24,883 edges): u the unit vector from node a to node b and
// q = (length - rest) + damping (v_b - v_a) . u. Each spring's force is then (k q) u, which
// sim/node_update.comp forms per node. Each invocation writes only its own edge's slot.
#include "common/layout.glsl"
#include "common/exact_math.glsl"
#include "sim/mass_spring.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) readonly buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_SPRING_EDGE) readonly buffer SpringEdges {
  SpringEdge edges[];
};
layout(std430, binding = BINDING_EDGE_STATE) writeonly buffer EdgeStates {
  vec4 edge_states[];
};
layout(std430, binding = BINDING_BODY_PARAMS) readonly buffer BodyParameters {
  BodyParams body_params[];
};
layout(std430, binding = BINDING_NODE_BODY) readonly buffer NodeBody {
  uint node_body[];
};

uniform uint u_edge_count;

void main() {
  const uint e = gl_GlobalInvocationID.x;
  if (e >= u_edge_count) return;  // the last work group reaches past the end
  const SpringEdge edge = edges[e];
  // An edge of frozen bodies keeps its state (src/core/sim/frozen_bodies.h; the CPU skips
  // whole batches of such edges: the values are the same).
  if (body_params[node_body[edge.a]].frozen != 0.0 && body_params[node_body[edge.b]].frozen != 0.0)
    return;
  edge_states[e] = spring_edge_state(positions[edge.a].xyz, positions[edge.b].xyz,
                                     velocities[edge.a].xyz, velocities[edge.b].xyz,
                                     edge.rest_length, edge.damping);
}
