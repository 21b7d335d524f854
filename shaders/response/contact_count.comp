#version 430
// The contact response's count pass: one invocation per node counts its active constraints
// (the activity pass's flag in the w of each constraint's first correction slot) over its CSR
// list of constraint corners, the contacts (at 2 n) apart from the volume constraints (2 n + 1,
// those from u_first_volume on): the solve passes solve the two groups one after the other,
// each node weighing by its count in the group. Each invocation writes only its own node's
// counts. The CPU backend
// sums the same integer counts from its compacted list of active constraints
// (src/cpu/cpu_contact_response.cpp): a count does not depend on the order it is summed in.
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_CONTACT_CORRECTION) readonly buffer ContactCorrections {
  vec4 corrections[];
};
layout(std430, binding = BINDING_NODE_CONTACT_OFFSET) readonly buffer NodeContactOffsets {
  uint node_contact_offset[];
};
layout(std430, binding = BINDING_NODE_CONTACT_LIST) readonly buffer NodeContactList {
  uint node_contact_list[];
};
layout(std430, binding = BINDING_NODE_CONTACT_COUNT) writeonly buffer NodeContactCounts {
  uint node_contact_count[];
};

uniform uint u_node_count;
uniform uint u_first_volume;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= u_node_count) return;  // the last work group reaches past the end
  const uint begin = node_contact_offset[i];
  const uint end = node_contact_offset[i + 1u];
  uint count[2] = uint[2](0u, 0u);
  for (uint e = begin; e < end; ++e) {
    const uint p = node_contact_list[e] / 4u;
    if (corrections[8u * p].w > 0.0) ++count[p < u_first_volume ? 0 : 1];
  }
  node_contact_count[2u * i] = count[0];
  node_contact_count[2u * i + 1u] = count[1];
  // The slot after the nodes' counts is the node pass's stray flag: cleared here, before it.
  if (i == 0u) node_contact_count[2u * u_node_count] = 0u;
}
