#version 430
// The contact response's activity pass: one invocation per constraint p of [u_pair_begin,
// u_pair_end) says whether it acts now (1, else 0) in its acting flag, which the compaction pass
// turns into the acting list. Two dispatches a projection
// (src/core/response/contact_constraints.h): the contacts (contact_awake, then contact_active:
// only an awake constraint looks at its geometry), each active one that guards volume
// constraints (guards_volumes) stamping its nodes with the projection (u_projection: every
// writer of a node writes the same value); then the volume constraints (volume_watched), which
// read the stamps. No two invocations write the same slot.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) readonly buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_CONTACT_ACTING) writeonly buffer ContactActing {
  uint contact_acting[];
};
layout(std430, binding = BINDING_PROJECTION_START) readonly buffer ProjectionStarts {
  vec4 projection_starts[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_NODE_GUARD) buffer NodeGuards {
  uint node_guard[];
};

uniform uint u_pair_begin;
uniform uint u_pair_end;
uniform float u_elapsed;
uniform float u_h;
uniform uint u_projection;

void main() {
  const uint p = u_pair_begin + gl_GlobalInvocationID.x;
  if (p >= u_pair_end) return;  // the last work group reaches past the end
  const ContactPair pair = pairs[p];
  vec4 x[4];
  bool acting;
  if (pair.kind == CONTACT_VOLUME) {
    vec4 v[4];
    bool guarded = false;
    for (uint i = 0u; i < 4u; ++i) {
      x[i] = positions[pair.nodes[i]];
      v[i] = velocities[pair.nodes[i]];
      guarded = guarded || node_guard[pair.nodes[i]] == u_projection;
    }
    acting = volume_watched(pair, x, v, u_h, guarded);
  } else {
    float deviation[4];
    for (uint i = 0u; i < 4u; ++i) deviation[i] = projection_starts[pair.nodes[i]].w;
    acting = contact_awake(pair, deviation, u_elapsed);
    if (acting) {
      for (uint i = 0u; i < 4u; ++i) x[i] = positions[pair.nodes[i]];
      vec3 window_start[4];
      const bool reads = reads_window_start(pair);
      for (uint i = 0u; i < 4u; ++i)
        window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
      acting = contact_active(pair, x, window_start);
    }
    if (acting && guards_volumes(pair)) {
      for (uint i = 0u; i < 4u; ++i) node_guard[pair.nodes[i]] = u_projection;
    }
  }
  contact_acting[p] = acting ? 1u : 0u;
}
