#version 430
// The contact response's activity pass: one invocation per constraint p says whether it acts
// now (contact_active in src/core/response/contact_constraints.h), in the w of its first
// correction slot (8 p), which the count pass reads before the solve pass overwrites it. No two
// invocations write the same slot.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_CONTACT_CORRECTION) writeonly buffer ContactCorrections {
  vec4 corrections[];
};

uniform uint u_pair_count;

void main() {
  const uint p = gl_GlobalInvocationID.x;
  if (p >= u_pair_count) return;  // the last work group reaches past the end
  const ContactPair pair = pairs[p];
  vec4 x[4];
  for (uint i = 0u; i < 4u; ++i) x[i] = positions[pair.nodes[i]];
  corrections[8u * p] = vec4(0.0, 0.0, 0.0, contact_active(pair, x) ? 1.0 : 0.0);
}
