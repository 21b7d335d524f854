#version 430
// The proximity search's scan: offsets[i] = counts[0] + ... + counts[i - 1], offsets[n] = the
// total. One work group: each invocation sums a contiguous chunk, invocation 0 scans the chunk
// sums, each invocation then writes its chunk's offsets. Integer sums: exact in any order.
#include "proximity/proximity_buffers.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BINDING_PROXIMITY_COUNTS) readonly buffer Counts {
  uint counts[];
};
layout(std430, binding = BINDING_PROXIMITY_OFFSETS) writeonly buffer Offsets {
  uint offsets[];
};

uniform uint u_item_count;

shared uint chunk_start[256];

void main() {
  const uint t = gl_LocalInvocationID.x;
  const uint per = (u_item_count + 255u) / 256u;
  const uint begin = min(t * per, u_item_count);
  const uint end = min(begin + per, u_item_count);
  uint sum = 0u;
  for (uint i = begin; i < end; ++i) sum += counts[i];
  chunk_start[t] = sum;
  memoryBarrierShared();
  barrier();
  if (t == 0u) {
    uint running = 0u;
    for (uint k = 0u; k < 256u; ++k) {
      const uint s = chunk_start[k];
      chunk_start[k] = running;
      running += s;
    }
    offsets[u_item_count] = running;
  }
  memoryBarrierShared();
  barrier();
  uint running = chunk_start[t];
  for (uint i = begin; i < end; ++i) {
    offsets[i] = running;
    running += counts[i];
  }
}
