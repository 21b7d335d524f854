#version 430
// The narrow phase over a candidate list (the bvh and octree-compact broad phases): one
// invocation per candidate face pair of SSBO 28, grid-stride when the candidates outnumber the
// dispatch (the host dispatches it indirectly, with arguments from collision/dispatch_args.comp).
// Candidates past the capacity were counted but not stored; the host reruns the pass then.
#include "collision/candidate_pairs.glsl"
#include "collision/narrow_phase.glsl"
#include "common/layout.glsl"

layout(local_size_x = 64) in;

void main() {
  const uint count = min(counters.candidates, u_candidate_capacity);
  const uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint c = gl_GlobalInvocationID.x; c < count; c += stride) {
    const uvec2 pair = candidate_pairs[c];
    test_face_pair(pair.x, pair.y);
  }
}
