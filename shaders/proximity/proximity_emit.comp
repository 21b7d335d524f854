#version 430
// The proximity search's emit pass: one invocation per work item reruns the count pass's query
// (the same decisions on the same floats) and writes its candidates from its scanned offset,
// in the C++ order: CpuProximity::find's order.
#include "proximity/proximity_query.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_PROXIMITY_OFFSETS) readonly buffer Offsets {
  uint offsets[];
};
layout(std430, binding = BINDING_PROXIMITY_CANDIDATES) writeonly buffer Candidates {
  ProximityCandidate candidates[];
};

uint g_next;

void proximity_emit(ProximityCandidate c) { candidates[g_next++] = c; }

void main() {
  const uint item = gl_GlobalInvocationID.x;
  if (item >= u_item_count) return;  // the last work group reaches past the end
  g_next = offsets[item];
  run_proximity_item(item);
}
