#version 430
// Test probe for shaders/collision/tri_tri_intersection.glsl: one invocation per triangle pair,
// so that tests/gl/tri_tri_gl_test.cpp can compare every answer with the C++ function.
#include "collision/tri_tri_intersection.glsl"

layout(local_size_x = 64) in;

// Pair i: p = triangles[6i .. 6i+2], q = triangles[6i+3 .. 6i+5] (xyz; w unused).
layout(std430, binding = 0) readonly buffer Triangles { vec4 triangles[]; };
// Pair i: (intersect, coplanar, 0, 0).
layout(std430, binding = 1) writeonly buffer Flags { uvec4 flags[]; };
// Pair i: segments[2i], segments[2i+1] (xyz; w = 0).
layout(std430, binding = 2) writeonly buffer Segments { vec4 segments[]; };

uniform uint u_count;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  vec3 p[3];
  vec3 q[3];
  for (uint k = 0u; k < 3u; ++k) {
    p[k] = triangles[6u * i + k].xyz;
    q[k] = triangles[6u * i + 3u + k].xyz;
  }
  const TriTriResult r = tri_tri_intersect(p, q);
  flags[i] = uvec4(r.intersect ? 1u : 0u, r.coplanar ? 1u : 0u, 0u, 0u);
  segments[2u * i] = vec4(r.segment0, 0.0);
  segments[2u * i + 1u] = vec4(r.segment1, 0.0);
}
