#version 430
// The contact response's deviation pass, first in every projection: one invocation per node
// records how far the node is from its straight path (path_deviation in
// src/core/response/contact_constraints.h), which the activity pass reads to leave asleep the
// constraints that cannot act yet. Each invocation writes only its own node's slot.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_NODE_MOTION) readonly buffer NodeMotion {
  vec4 node_motion[];
};
layout(std430, binding = BINDING_NODE_DEVIATION) writeonly buffer NodeDeviation {
  float node_deviation[];
};

uniform uint u_node_count;
uniform float u_elapsed;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  node_deviation[i] = path_deviation(positions[i].xyz, frame_start[i], node_motion[i], u_elapsed);
}
