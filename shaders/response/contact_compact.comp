#version 430
// The contact response's compaction pass, after the activity pass: lists the acting constraints
// in ascending order (the CPU backend's acting list, src/cpu/cpu_contact_response.cpp), rewrites
// each constraint's acting flag to 1 + its place in that list (0: does not act), counts the
// acting contacts and constraints, and clears the touched-node count for the count pass. The
// sweeps, residual and slide passes then run over the acting constraints and touched nodes alone
// (on the impact scene about 2,200 of 55,000 listed constraints, 2,400 of 40,000 nodes).
//
// One work group: each invocation takes a contiguous chunk of the constraints, counts its acting
// ones, the group scans the 256 counts (one invocation, in order), and each invocation writes its
// chunk's entries from its offset. Integer counts: the list is the same whatever the schedule.
// One group reads the flags once and writes the list once, a few microseconds for 10^5
// constraints on a GPU, against a multi-group scan's extra passes and barriers.
#include "response/response_work_buffers.glsl"

#define COMPACT_GROUP_SIZE 256u
layout(local_size_x = 256) in;

layout(std430, binding = BINDING_CONTACT_ACTING) buffer ContactActing {
  uint contact_acting[];
};
layout(std430, binding = BINDING_ACTING_LIST) writeonly buffer ActingList {
  uint acting_list[];
};
layout(std430, binding = BINDING_RESPONSE_STATE) buffer ResponseState {
  uint response_state[];
};

uniform uint u_pair_count;    // the constraints: [0, u_pair_count)
uniform uint u_first_volume;  // the first volume constraint: the contacts are those before it

shared uint chunk_offset[COMPACT_GROUP_SIZE];  // acting constraints before each chunk
shared uint chunk_contacts[COMPACT_GROUP_SIZE];  // each chunk's acting contacts

void main() {
  const uint t = gl_LocalInvocationID.x;
  const uint chunk = u_pair_count / COMPACT_GROUP_SIZE +
                     (u_pair_count % COMPACT_GROUP_SIZE != 0u ? 1u : 0u);
  const uint begin = min(t * chunk, u_pair_count);
  const uint end = min(begin + chunk, u_pair_count);
  uint acting = 0u;
  uint contacts = 0u;
  for (uint p = begin; p < end; ++p) {
    if (contact_acting[p] != 0u) {
      ++acting;
      if (p < u_first_volume) ++contacts;
    }
  }
  chunk_offset[t] = acting;
  chunk_contacts[t] = contacts;
  memoryBarrierShared();
  barrier();
  if (t == 0u) {
    uint total = 0u;
    uint total_contacts = 0u;
    for (uint c = 0u; c < COMPACT_GROUP_SIZE; ++c) {
      const uint count = chunk_offset[c];
      chunk_offset[c] = total;
      total += count;
      total_contacts += chunk_contacts[c];
    }
    response_state[RESPONSE_ACTING_CONTACTS] = total_contacts;
    response_state[RESPONSE_ACTING_TOTAL] = total;
    response_state[RESPONSE_TOUCHED_NODES] = 0u;
  }
  memoryBarrierShared();
  barrier();
  uint a = chunk_offset[t];
  for (uint p = begin; p < end; ++p) {
    if (contact_acting[p] != 0u) {
      acting_list[a] = p;
      ++a;
      contact_acting[p] = a;
    }
  }
}
