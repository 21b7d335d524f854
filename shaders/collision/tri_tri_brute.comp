#version 430
// The paper's baseline ("original method"): every surface face of mesh a against every one of
// mesh b, without boxes. Invocation (x, y, z) tests face x of mesh pair u_pair_first + z's mesh
// a against face y of its mesh b. The host dispatches the chunk's largest N x M; invocations
// past a pair's own faces return. counters.candidates counts the pairs tested. A mesh paired
// with itself (self-collision) tests its pairs x < y (test_face_pair skips the others).
#include "collision/narrow_phase.glsl"
#include "collision/meshes.glsl"
#include "common/layout.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = BINDING_BODY_PAIR) readonly buffer BodyPairs {
  BodyPair mesh_pairs[];
};

uniform uint u_pair_first;  // the chunk's first mesh pair

void main() {
  const uint x = gl_GlobalInvocationID.x;
  const uint y = gl_GlobalInvocationID.y;
  const BodyPair pair = mesh_pairs[u_pair_first + gl_GlobalInvocationID.z];
  const MeshInfo a = meshes[pair.a];
  const MeshInfo b = meshes[pair.b];
  // Each face pair in range is tested: the group's first invocation counts the group's share
  // of them at once (counters.candidates), rather than one atomicAdd per invocation.
  if (gl_LocalInvocationIndex == 0u) {
    const uvec2 origin = gl_WorkGroupID.xy * gl_WorkGroupSize.xy;
    const uint nx = a.face_count > origin.x ? min(a.face_count - origin.x, gl_WorkGroupSize.x) : 0u;
    const uint ny = b.face_count > origin.y ? min(b.face_count - origin.y, gl_WorkGroupSize.y) : 0u;
    uint tested = nx * ny;
    if (pair.a == pair.b) {  // a mesh against itself: the pairs x < y only, as tested below
      tested = 0u;
      for (uint i = 0u; i < nx; ++i) {
        const uint first_y = max(origin.y, origin.x + i + 1u);
        tested += origin.y + ny > first_y ? origin.y + ny - first_y : 0u;
      }
    }
    if (tested > 0u) atomicAdd(counters.candidates, tested);
  }
  if (x >= a.face_count || y >= b.face_count) return;
  test_face_pair(a.face_offset + x, b.face_offset + y);
}
