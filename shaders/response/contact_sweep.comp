#version 430
// The contact response's sweep (after the compaction and count passes; once per iteration): one
// work group sweeps the acting constraints colour by colour (the host's order,
// src/core/response/sweep_order.h: the contacts' colours, then the volume constraints'), each
// constraint solved on its nodes as the colours before left them (solve_contact) and its
// corrections applied to its four nodes at once (apply_correction); a barrier after each colour
// makes its writes visible to the next. No two constraints of a colour share a node, so a
// colour's invocations write disjoint nodes and their order changes no bit: the same sweep as
// the CPU backend's (src/cpu/cpu_contact_response.cpp), line for line. Each writes what its
// constraint has given to its impulse slots 3 a to 3 a + 2 and, in the last iteration, the
// corners where it slides on to its slide bits (the slide pass stamps the nodes after the
// sweep). One work group: a colour holds tens of constraints, and a barrier a colour is cheaper
// than a dispatch a colour.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BINDING_NODE_POSITION) coherent buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) coherent buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_CONTACT_PAIR) readonly buffer ContactPairs {
  ContactPair pairs[];
};
layout(std430, binding = BINDING_CONTACT_SLIDES) writeonly buffer ContactSlides {
  uint contact_slides[];
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
layout(std430, binding = BINDING_SWEEP_ORDER) readonly buffer SweepOrder {
  uint sweep_order[];
};
layout(std430, binding = BINDING_SWEEP_COLOURS) readonly buffer SweepColours {
  uint sweep_colours[];
};

uniform uint u_colours;          // colours in all
uniform uint u_contact_colours;  // the first u_contact_colours are the contacts'
uniform float u_h;
uniform float u_friction_static;
uniform float u_friction_dynamic;
uniform float u_restitution;
uniform float u_max_untangle_step;
uniform bool u_first_iteration;
uniform bool u_last_iteration;
uniform uint u_substep;

// One constraint, entry a of the acting list: the CPU backend's `solve`, line for line.
void solve(uint a, bool contact) {
  const ContactPair pair = pairs[acting_list[a]];
  vec4 x[4], v[4];
  uint count[4] = uint[4](0u, 0u, 0u, 0u);
  for (uint i = 0u; i < 4u; ++i) {
    x[i] = positions[pair.nodes[i]];
    v[i] = velocities[pair.nodes[i]];
  }
  // A volume constraint reads no count, projection start, window start or slide history.
  vec4 start[4] = vec4[4](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
  vec3 window_start[4] = vec3[4](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  uint history = NONE_SLID;
  if (contact) {
    uint slid[4];
    for (uint i = 0u; i < 4u; ++i) {
      count[i] = node_contact_count[2u * pair.nodes[i]];
      start[i] = projection_starts[pair.nodes[i]];
      slid[i] = node_slid[pair.nodes[i]];
    }
    const bool reads = reads_window_start(pair);
    for (uint i = 0u; i < 4u; ++i)
      window_start[i] = reads ? frame_start[pair.nodes[i]].xyz : vec3(0.0);
    history = slid_before(x, slid, u_substep);
  }
  vec4 correction[8];
  vec4 given[3] = vec4[3](impulses[3u * a], impulses[3u * a + 1u], impulses[3u * a + 2u]);
  solve_contact(pair, x, v, count, start, window_start,
                ContactConstants(u_h, u_friction_static, u_friction_dynamic, u_restitution,
                                 u_max_untangle_step, 0.0),
                u_first_iteration, u_last_iteration, history, given, correction);
  uint slides = 0u;
  for (uint i = 0u; i < 4u; ++i) {
    vec4 position = x[i];
    vec4 velocity = v[i];
    apply_correction(position, velocity, correction[2u * i].xyz, correction[2u * i + 1u].xyz);
    positions[pair.nodes[i]] = position;
    velocities[pair.nodes[i]] = velocity;
    if (correction[2u * i + 1u].w > 0.0) slides |= 1u << i;
  }
  contact_slides[a] = slides;
  impulses[3u * a] = given[0];
  impulses[3u * a + 1u] = given[1];
  impulses[3u * a + 2u] = given[2];
}

void main() {
  for (uint c = 0u; c < u_colours; ++c) {
    const uint begin = sweep_colours[c];
    const uint end = sweep_colours[c + 1u];
    for (uint e = begin + gl_LocalInvocationID.x; e < end; e += gl_WorkGroupSize.x)
      solve(sweep_order[e], c < u_contact_colours);
    // The next colour reads the nodes this one wrote.
    memoryBarrierBuffer();
    barrier();
  }
}
