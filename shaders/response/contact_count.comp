#version 430
// The contact response's count pass, after the compaction pass: one invocation per node walks
// its CSR list of constraint corners (slots 4 p + k, ascending) and lists its active ones, as
// acting-list slots 4 a + k (a: the constraint's place in the acting list), from its list
// offset on in the node active-slot buffer: the slide pass then looks through only those. It
// counts them, the contacts (at 2 n) apart from the volume constraints (2 n + 1, those from
// u_first_volume on, last in the list): a contact's nodes weigh by their counts of active
// contacts in the sweeps (mass splitting), and a node with either count is touched. A node with
// an active slot adds itself to the touched nodes (their order is the atomics' and changes
// nothing: the slide pass writes each node alone). Each invocation writes only its own node's counts and slots. The CPU backend
// builds the same counts and slot lists from its acting list (src/cpu/cpu_contact_response.cpp).
#include "common/layout.glsl"
#include "response/response_work_buffers.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_CONTACT_OFFSET) readonly buffer NodeContactOffsets {
  uint node_contact_offset[];
};
layout(std430, binding = BINDING_NODE_CONTACT_LIST) readonly buffer NodeContactList {
  uint node_contact_list[];
};
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) writeonly buffer NodeContactCounts {
  uint node_contact_count[];
};
layout(std430, binding = BINDING_CONTACT_ACTING) readonly buffer ContactActing {
  uint contact_acting[];
};
layout(std430, binding = BINDING_NODE_ACTIVE_SLOT) writeonly buffer NodeActiveSlots {
  uint node_active_slot[];
};
layout(std430, binding = BINDING_TOUCHED_NODE) writeonly buffer TouchedNodes {
  uint touched_node[];
};
layout(std430, binding = BINDING_RESPONSE_STATE) buffer ResponseState {
  uint response_state[];
};

uniform uint u_node_count;
uniform uint u_first_volume;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  const uint begin = node_contact_offset[i];
  const uint end = node_contact_offset[i + 1u];
  uint count[2] = uint[2](0u, 0u);
  uint listed = begin;
  for (uint e = begin; e < end; ++e) {
    const uint slot = node_contact_list[e];
    const uint p = slot / 4u;
    const uint place = contact_acting[p];  // 1 + the acting-list place, 0: not acting
    if (place == 0u) continue;
    node_active_slot[listed] = 4u * (place - 1u) + slot % 4u;
    ++listed;
    ++count[p < u_first_volume ? 0 : 1];
  }
  node_contact_count[2u * i] = count[0];
  node_contact_count[2u * i + 1u] = count[1];
  if (listed != begin) touched_node[atomicAdd(response_state[RESPONSE_TOUCHED_NODES], 1u)] = i;
}
