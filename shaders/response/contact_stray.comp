#version 430
// The contact response's stray pass, last in every projection: one invocation per node flags
// whether it has strayed beyond its reach (strayed in src/core/response/contact_constraints.h),
// so that a new proximity search must start before the next substep. Every writer writes the
// same 1, so the flag is the same whatever the order (the CPU's OR of the same booleans).
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"
#include "response/response_work_buffers.glsl"

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
layout(std430, binding = BINDING_RESPONSE_STATE) buffer ResponseState {
  uint response_state[];
};

uniform uint u_node_count;
uniform float u_elapsed;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  if (strayed(positions[i], frame_start[i], node_motion[i], u_elapsed))
    response_state[RESPONSE_STRAY_FLAG] = 1u;
}
