#version 430
// The contact response's node pass: one invocation per node sums its constraints' corrections over
// its CSR list in list order (gather_correction in src/core/response/contact_constraints.h, written
// out here because GLSL cannot pass a buffer to a function), applies the sums to its own position
// and velocity (apply_correction) and, in a projection's last pass (u_watch_reach), flags a stray
// beyond its reach (strayed); after the contacts' last iteration (u_record_slide) it records a
// slide of one of its contacts (the w of the velocity slots). Only the slots of one group's
// constraints, [u_pair_begin, u_pair_end), are summed (the contacts, then the volume constraints:
// contact_pairs.comp); slots of constraints that do not act (the flag in the w of a constraint's
// first slot) are skipped, as the CPU skips them. Each invocation reads and writes only its own
// node's position and velocity.
#include "common/layout.glsl"
#include "response/contact_constraints.glsl"

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
layout(std430, binding = BINDING_NODE_CONTACT_LIST) readonly buffer NodeContactList {
  uint node_contact_list[];
};
// The counts, and after them (at u_node_count) the flag a node sets when it strays.
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) buffer NodeContactCounts {
  uint node_contact_count[];
};
layout(std430, binding = BINDING_FRAME_START) readonly buffer FrameStarts {
  vec4 frame_start[];
};
layout(std430, binding = BINDING_NODE_MOTION) readonly buffer NodeMotion {
  vec4 node_motion[];
};
layout(std430, binding = BINDING_NODE_SLID) buffer NodeSlid {
  uint node_slid[];
};

uniform uint u_node_count;
uniform uint u_pair_begin;
uniform uint u_pair_end;
uniform float u_elapsed;
uniform bool u_watch_reach;
uniform bool u_record_slide;
uniform uint u_substep;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  // gather_correction, line for line.
  const uint begin = node_contact_offset[i];
  const uint end = node_contact_offset[i + 1u];
  precise vec3 dx = vec3(0.0);
  precise vec4 dv = vec4(0.0);
  for (uint e = begin; e < end; ++e) {
    const uint slot = node_contact_list[e];
    const uint p = slot / 4u;
    if (p < u_pair_begin || p >= u_pair_end) continue;  // another group's
    if (!(corrections[8u * p].w > 0.0)) continue;
    dx += corrections[2u * slot].xyz;
    dv += corrections[2u * slot + 1u];
  }
  vec4 position = positions[i];
  vec4 velocity = velocities[i];
  // After the contacts' last iteration: a free node one of whose contacts slides on records
  // the substep (the CPU node pass's rule).
  if (u_record_slide && dv.w > 0.0 && position.w > 0.0) node_slid[i] = u_substep;
  apply_correction(position, velocity, dx, dv.xyz);
  // Every writer writes the same 1, so the flag is the same whatever the order.
  if (u_watch_reach && strayed(position, frame_start[i], node_motion[i], u_elapsed)) {
    node_contact_count[2u * u_node_count] = 1u;
  }
  positions[i] = position;
  velocities[i] = velocity;
}
