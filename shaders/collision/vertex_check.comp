#version 430
// The finiteness check of one mesh's positions in a caller's GL buffer, before a pass reads
// them (GlCollision::find_non_finite): one invocation per vertex (grid-stride); a vertex with a
// NaN or infinite coordinate lowers the mesh's entry of SSBO 34 to its index with atomicMin, so
// that the host reads the first bad vertex of every mesh at once. One dispatch per mesh, with
// the caller's buffer bound at SSBO 0 and the mesh's layout in uniforms (the same words
// vertex_position reads, collision/surface.glsl).
//
// The test is on the bits (exponent all ones), not isnan/isinf: a compiler may assume floats
// finite and fold x != x away, and then the check would pass what the narrow phase chokes on.
#include "collision/gl_work_buffers.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BINDING_NODE_POSITION) readonly buffer VertexWords {
  float vertex_words[];
};
layout(std430, binding = BINDING_NON_FINITE) buffer NonFinite {
  uint first_non_finite[];  // per mesh
};

uniform uint u_mesh;          // the entry of SSBO 34 to lower
uniform uint u_vertex_count;  // the mesh's vertices
uniform uint u_offset;        // vertex 0's first float
uniform uint u_stride;        // floats from one vertex to the next

bool non_finite(float x) {
  return (floatBitsToUint(x) & 0x7F800000u) == 0x7F800000u;
}

void main() {
  // Grid-stride: a mesh may have more vertices than one dispatch has invocations.
  const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint v = gl_GlobalInvocationID.x; v < u_vertex_count; v += stride) {
    const uint w = u_offset + v * u_stride;
    if (non_finite(vertex_words[w]) || non_finite(vertex_words[w + 1u]) ||
        non_finite(vertex_words[w + 2u])) {
      atomicMin(first_non_finite[u_mesh], v);
      return;  // later vertices of this invocation are higher
    }
  }
}
