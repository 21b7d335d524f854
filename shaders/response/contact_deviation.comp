#version 430
// The contact response's deviation pass, first in every projection: one invocation per node
// records the node's projection start (projection_start in
// src/core/response/contact_constraints.h): its position less h x its velocity, from which the
// solve pass's hold measures how far pushes carried a contact's point, and how far the node is
// from its straight path, which the activity pass reads to leave asleep the constraints that
// cannot act yet. Each invocation writes only its own node's slot.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) readonly buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_NODE_MOTION) readonly buffer NodeMotion {
  vec4 node_motion[];
};
layout(std430, binding = BINDING_PROJECTION_START) writeonly buffer ProjectionStarts {
  vec4 projection_starts[];
};

uniform uint u_node_count;
uniform float u_h;
uniform float u_elapsed;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  projection_starts[i] = projection_start(positions[i], velocities[i], u_h, frame_start[i],
                                          node_motion[i], u_elapsed);
}
