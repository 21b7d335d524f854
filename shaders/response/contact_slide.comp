#version 430
// The contact response's slide pass, after a last-iteration sweep (contact_sweep.comp): one
// invocation per touched node (the count pass's list, dispatched indirectly) looks through its
// active contacts' slots (4 a + corner, its list's first node_contact_count[2 n]) and, where one
// slides on at its corner (the sweep's slide bits) and the node is free, records the substep: a
// contact slid through it (slid_before). The CPU backend stamps the same nodes from its acting
// contacts after its sweep. Each invocation writes only its own node's stamp.
#include "common/layout.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer NodePositions {
  vec4 positions[];
};
layout(std430, binding = BINDING_CONTACT_SLIDES) readonly buffer ContactSlides {
  uint contact_slides[];
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

uniform uint u_substep;

void main() {
  const uint t = gl_GlobalInvocationID.x;
  if (t >= response_state[RESPONSE_TOUCHED_NODES]) return;  // the last group reaches past
  const uint i = touched_node[t];
  if (!(positions[i].w > 0.0)) return;  // a fixed node's motion is prescribed
  const uint begin = node_contact_offset[i];
  const uint end = begin + node_contact_count[2u * i];  // its contacts' slots come first
  for (uint e = begin; e < end; ++e) {
    const uint slot = node_active_slot[e];
    if ((contact_slides[slot / 4u] >> (slot % 4u) & 1u) != 0u) {
      node_slid[i] = u_substep;
      return;
    }
  }
}
