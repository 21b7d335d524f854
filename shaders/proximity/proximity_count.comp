#version 430
// The proximity search's count pass: one invocation per work item (a face of a mesh pair's
// mesh a, proximity_query.glsl) counts its candidates into its own slot.
#include "proximity/proximity_query.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_PROXIMITY_COUNTS) writeonly buffer Counts {
  uint counts[];
};

uint g_count;

void proximity_emit(ProximityCandidate c) { ++g_count; }

void main() {
  const uint item = gl_GlobalInvocationID.x;
  if (item >= u_item_count) return;  // the last work group reaches past the end
  g_count = 0u;
  run_proximity_item(item);
  counts[item] = g_count;
}
