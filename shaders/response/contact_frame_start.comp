#version 430
// The contact response's frame start: one invocation per node records where the node starts
// the search window and how far it may stray from its path (its reach), which the stray pass
// watches: frame_start[i] = vec4(position.xyz, node_motion[i].w). Within a window whose
// constraints were replaced (update_frame: reaches raised), the start stays and only the
// reach is taken.
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_MOTION) readonly buffer NodeMotion {
  vec4 node_motion[];
};
layout(std430, binding = BINDING_FRAME_START) buffer FrameStarts {
  vec4 frame_start[];
};

uniform uint u_node_count;
uniform uint u_keep_positions;  // 1: keep each start, take the reach

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  const vec3 start = u_keep_positions != 0u ? frame_start[i].xyz : positions[i].xyz;
  frame_start[i] = vec4(start, node_motion[i].w);
}
