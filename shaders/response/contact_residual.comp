#version 430
// The contact response's residual pass, after a projection's iterations: one invocation per
// acting constraint (the acting list, dispatched indirectly; contacts and volume constraints)
// flags whether it is still violated (contact_violated in
// src/core/response/contact_constraints.h), in the state buffer: then another iteration is due.
// Every writer writes the same 1, so the flag is the same whatever the order (the CPU's OR of
// the same booleans).
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_ACTING_LIST) readonly buffer ActingList {
  uint acting_list[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_RESPONSE_STATE) buffer ResponseState {
  uint response_state[];
};

void main() {
  const uint a = gl_GlobalInvocationID.x;
  // The last work group reaches past the end.
  if (a >= response_state[RESPONSE_ACTING_TOTAL]) return;
  const ContactPair pair = pairs[acting_list[a]];
  vec4 x[4];
  for (uint i = 0u; i < 4u; ++i) x[i] = positions[pair.nodes[i]];
  vec3 window_start[4];
  const bool reads = reads_window_start(pair);
  for (uint i = 0u; i < 4u; ++i)
    window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
  if (contact_violated(pair, x, window_start)) response_state[RESPONSE_RESIDUAL_FLAG] = 1u;
}
