#version 430
// The contact response's activity pass: one invocation per constraint p says whether it acts
// now (contact_awake, then contact_active, in src/core/response/contact_constraints.h: only an
// awake constraint looks at its geometry), in the w of its first correction slot (8 p), which
// the count pass reads before the solve pass overwrites it. No two invocations write the same
// slot.
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
layout(std430, binding = BINDING_PROJECTION_START) readonly buffer ProjectionStarts {
  vec4 projection_starts[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};

uniform uint u_pair_count;
uniform float u_elapsed;

void main() {
  const uint p = gl_GlobalInvocationID.x;
  if (p >= u_pair_count) return;  // the last work group reaches past the end
  const ContactPair pair = pairs[p];
  float deviation[4];
  for (uint i = 0u; i < 4u; ++i) deviation[i] = projection_starts[pair.nodes[i]].w;
  bool acting = contact_awake(pair, deviation, u_elapsed);
  if (acting) {
    vec4 x[4];
    for (uint i = 0u; i < 4u; ++i) x[i] = positions[pair.nodes[i]];
    vec3 window_start[4];
    const bool reads = reads_window_start(pair);
    for (uint i = 0u; i < 4u; ++i)
      window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
    acting = contact_active(pair, x, window_start);
  }
  corrections[8u * p] = vec4(0.0, 0.0, 0.0, acting ? 1.0 : 0.0);
}
