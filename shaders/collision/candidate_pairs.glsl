// The candidate face pairs (SSBO 28) that a broad phase hands to the narrow phase
// (collision/tri_tri_candidates.comp): global face indices, face_a of the mesh pair's
// lower-numbered mesh (the FacePair convention). A pair's slot comes from atomicAdd on
// counters.candidates, which counts every append, those past the capacity included: a count
// above u_candidate_capacity tells the host that the buffer overflowed (GlCollision::
// complete_pass then grows it and reruns the pass). Nothing is written past the capacity.
#include "collision/counters.glsl"
#include "common/layout.glsl"

layout(std430, binding = BINDING_CANDIDATE_PAIR) buffer CandidatePairs {
  uvec2 candidate_pairs[];
};

uniform uint u_candidate_capacity;  // uvec2 slots in SSBO 28

// Only face_a < face_b is appended: within one mesh (self-collision) the broad phases meet
// each pair in both orders, and the narrow phase keeps the first (cpu_narrow_phase.h).
void append_candidate(uint face_a, uint face_b) {
  if (face_a >= face_b) return;
  const uint slot = atomicAdd(counters.candidates, 1u);
  if (slot < u_candidate_capacity) candidate_pairs[slot] = uvec2(face_a, face_b);
}
