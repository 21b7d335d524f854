#version 430
// The contact response's residual pass, after a projection's iterations (those asked, then each
// one more): one invocation
// per constraint p (contacts and volume constraints) that acts takes its margin
// (residual_margin in src/core/response/contact_constraints.h) into the least of its kind, as
// keys (residual_key) at u_node_count x 2 + 1 (contacts) and + 2 (volume constraints) of the
// counts buffer, which the host set to the largest key: atomicMin gives the same key whatever
// the order (the CPU's minimum of the same keys). The host decides from them whether another
// iteration is due (response::iterate_on).
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
// The counts, the stray flag, then (at 2 x u_node_count + 1 and + 2) this pass's two keys.
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
  const uint key = residual_key(residual_margin(pair, x, window_start));
  if (key == 0xffffffffu) return;  // the keys start there: no write needed
  const uint slot = 2u * u_node_count + (pair.kind == CONTACT_VOLUME ? 2u : 1u);
  atomicMin(node_contact_count[slot], key);
}
