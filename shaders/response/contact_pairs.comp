#version 430
// The contact response's solve pass (after the compaction and count passes; once per Jacobi
// iteration): one invocation per acting constraint, entry a of the acting list (constraint p),
// reads its four nodes' positions and velocities and writes their corrections to its own
// slots: corner k's at 2 (4 a + k) (position) and 2 (4 a + k) + 1 (velocity) (solve_contact),
// and what it has given over the substep's iterations to its own impulse slots 3 a to 3 a + 2;
// it reads its free nodes' slide stamps (the node pass writes them after the last iteration)
// and projection starts (the deviation pass's). Dispatched indirectly over one group: the
// acting contacts (u_group 0, the acting list's first RESPONSE_ACTING_CONTACTS entries) or the
// acting volume constraints (1, the rest), its nodes weighing by their counts in the group. No
// two invocations write the same slot, and nothing here writes a node.
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
layout(std430, binding = BINDING_CONTACT_CORRECTION) buffer ContactCorrections {
  vec4 corrections[];
};
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) readonly buffer NodeContactCounts {
  uint node_contact_count[];
};
layout(std430, binding = BINDING_CONTACT_IMPULSE) buffer ContactImpulses {
  vec4 impulses[];
};
layout(std430, binding = BINDING_NODE_SLID) readonly buffer NodeSlid {
  uint node_slid[];
};
layout(std430, binding = BINDING_PROJECTION_START) readonly buffer ProjectionStarts {
  vec4 projection_starts[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_ACTING_LIST) readonly buffer ActingList {
  uint acting_list[];
};
layout(std430, binding = BINDING_RESPONSE_STATE) readonly buffer ResponseState {
  uint response_state[];
};

uniform uint u_group;
uniform float u_h;
uniform float u_friction_static;
uniform float u_friction_dynamic;
uniform float u_restitution;
uniform float u_max_untangle_step;
uniform float u_inverse_relaxation;
uniform bool u_first_iteration;
uniform bool u_last_iteration;
uniform uint u_substep;

void main() {
  const uint contacts = response_state[RESPONSE_ACTING_CONTACTS];
  const uint a = (u_group == 0u ? 0u : contacts) + gl_GlobalInvocationID.x;
  // The last work group reaches past the group's end.
  if (a >= (u_group == 0u ? contacts : response_state[RESPONSE_ACTING_TOTAL])) return;
  const ContactPair pair = pairs[acting_list[a]];
  vec4 x[4], v[4], start[4];
  for (uint i = 0u; i < 4u; ++i) {
    x[i] = positions[pair.nodes[i]];
    v[i] = velocities[pair.nodes[i]];
    start[i] = projection_starts[pair.nodes[i]];
  }
  vec3 window_start[4];
  const bool reads = reads_window_start(pair);
  for (uint i = 0u; i < 4u; ++i)
    window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
  uint count[4], slid[4];
  for (uint i = 0u; i < 4u; ++i) {
    count[i] = node_contact_count[2u * pair.nodes[i] + u_group];
    slid[i] = node_slid[pair.nodes[i]];
  }
  vec4 correction[8];
  vec4 given[3] = vec4[3](impulses[3u * a], impulses[3u * a + 1u], impulses[3u * a + 2u]);
  solve_contact(pair, x, v, count, start, window_start,
                ContactConstants(u_h, u_friction_static, u_friction_dynamic, u_restitution,
                                 u_max_untangle_step, 0.0, u_inverse_relaxation),
                u_first_iteration, u_last_iteration, slid_before(x, slid, u_substep), given,
                correction);
  for (uint k = 0u; k < 8u; ++k) corrections[8u * a + k] = correction[k];
  impulses[3u * a] = given[0];
  impulses[3u * a + 1u] = given[1];
  impulses[3u * a + 2u] = given[2];
}
