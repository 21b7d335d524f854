#version 430
// Writes the contact response's glDispatchComputeIndirect arguments from the counts the
// compaction and count passes took, so that no count is read back to the host inside a
// projection: the residual pass over the acting constraints, the slide pass over the touched
// nodes. One invocation. A count of 0 gives 0 work groups, which GL runs as nothing.
#include "response/response_work_buffers.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = BINDING_RESPONSE_STATE) buffer ResponseState {
  uint response_state[];
};

uniform uint u_residual_local_size;  // contact_residual.comp's local size along x
uniform uint u_node_local_size;      // contact_slide.comp's

// Work groups of `local_size` invocations covering `count` (the counts are at most the
// constraints or nodes, which the host checked fit one dispatch).
uint groups_covering(uint count, uint local_size) {
  return count / local_size + (count % local_size != 0u ? 1u : 0u);
}

void write_args(uint word, uint groups) {
  response_state[word] = groups;
  response_state[word + 1u] = 1u;
  response_state[word + 2u] = 1u;
}

void main() {
  const uint total = response_state[RESPONSE_ACTING_TOTAL];
  write_args(RESPONSE_RESIDUAL_ARGS, groups_covering(total, u_residual_local_size));
  write_args(RESPONSE_SLIDE_PASS_ARGS,
             groups_covering(response_state[RESPONSE_TOUCHED_NODES], u_node_local_size));
}
