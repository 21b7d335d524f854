#version 430
// The contact response's residual pass, after a projection's iterations: one invocation per
// constraint p (contacts and volume constraints) flags whether it acts and is still violated
// (contact_violated in src/core/response/contact_constraints.h), at u_node_count x 2 + 1 of the
// counts buffer: then another iteration is due. Every writer writes the same 1, so the flag is
// the same whatever the order (the CPU's OR of the same booleans).
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_CONTACT_CORRECTION) readonly buffer ContactCorrections {
  vec4 corrections[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
// The counts, the stray flag, then (at 2 x u_node_count + 1) this pass's flag.
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) buffer NodeContactCounts {
  uint node_contact_count[];
};

uniform uint u_pair_count;  // the constraints: [0, u_pair_count)
uniform uint u_node_count;

void main() {
  const uint p = gl_GlobalInvocationID.x;
  if (p >= u_pair_count) return;  // the last work group reaches past the end
  if (!(corrections[8u * p].w > 0.0)) return;  // does not act in this projection
  const ContactPair pair = pairs[p];
  vec4 x[4];
  for (uint i = 0u; i < 4u; ++i) x[i] = positions[pair.nodes[i]];
  vec3 window_start[4];
  const bool reads = reads_window_start(pair);
  for (uint i = 0u; i < 4u; ++i)
    window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
  if (contact_violated(pair, x, window_start)) node_contact_count[2u * u_node_count + 1u] = 1u;
}
