#version 430
// The contact response's node pass: one invocation per touched node (the count pass's list,
// dispatched indirectly) sums its active corrections of one group (u_group: the contacts, then
// the volume constraints: contact_pairs.comp) over its active-slot list in list order
// (gather_correction in src/core/response/contact_constraints.h, written out here because GLSL
// cannot pass a buffer to a function) and applies the sums to its own position and velocity
// (apply_correction); after the contacts' last iteration (u_record_slide) it records a slide of
// one of its contacts (the w of the velocity slots). A node without an active constraint of
// the group is left alone, as the CPU leaves it. Each invocation reads and writes only its own
// node's position and velocity.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_NODE_VELOCITY) buffer NodeVelocities {
  vec4 velocities[];
};
layout(std430, binding = BINDING_CONTACT_CORRECTION) readonly buffer ContactCorrections {
  vec4 corrections[];
};
layout(std430, binding = BINDING_NODE_CONTACT_OFFSET) readonly buffer NodeContactOffsets {
  uint node_contact_offset[];
};
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) readonly buffer NodeContactCounts {
  uint node_contact_count[];
};
layout(std430, binding = BINDING_NODE_ACTIVE_SLOT) readonly buffer NodeActiveSlots {
  uint node_active_slot[];
};
layout(std430, binding = BINDING_TOUCHED_NODE) readonly buffer TouchedNodes {
  uint touched_node[];
};
layout(std430, binding = BINDING_RESPONSE_STATE) readonly buffer ResponseState {
  uint response_state[];
};
layout(std430, binding = BINDING_NODE_SLID) buffer NodeSlid {
  uint node_slid[];
};

uniform uint u_group;
uniform bool u_record_slide;
uniform uint u_substep;

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= response_state[RESPONSE_TOUCHED_NODES]) return;  // the last group reaches past
  const uint i = touched_node[t];
  // The group's slots: the contacts' first, then the volume constraints'.
  const uint begin = node_contact_offset[i] + (u_group == 0u ? 0u : node_contact_count[2u * i]);
  const uint end = begin + node_contact_count[2u * i + u_group];
  if (begin == end) return;
  // gather_correction, line for line.
  precise vec3 dx = vec3(0.0);
  precise vec4 dv = vec4(0.0);
  for (uint e = begin; e < end; ++e) {
    const uint slot = node_active_slot[e];
    dx += corrections[2u * slot].xyz;
    dv += corrections[2u * slot + 1u];
  }
  vec4 position = positions[i];
  vec4 velocity = velocities[i];
  // After the contacts' last iteration: a free node one of whose contacts slides on records
  // the substep (the CPU node pass's rule).
  if (u_record_slide && dv.w > 0.0 && position.w > 0.0) node_slid[i] = u_substep;
  apply_correction(position, velocity, dx, dv.xyz);
  positions[i] = position;
  velocities[i] = velocity;
}
