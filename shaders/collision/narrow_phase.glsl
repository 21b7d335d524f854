// The narrow phase shared by collision/tri_tri_octree.comp, collision/tri_tri_brute.comp and
// collision/tri_tri_candidates.comp: the exact test of one face pair and, when the faces
// intersect, its record in the outputs.
//
// Outputs, all reset by the host before a pass: the faces' flags (SSBO 5, set once with
// atomicExchange so that colliding_faces counts each face once), the counters (SSBO 23) and the
// face pairs (SSBO 10). A pair's slot comes from atomicAdd on counters.face_pairs, so the pairs
// land in no particular order; a count above u_pair_capacity tells the host that the buffer
// overflowed (it then grows the buffer and reruns the pass).
#include "collision/counters.glsl"
#include "collision/face_pair_intersection.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"

layout(std430, binding = BINDING_COLLISION_RESULT) buffer FaceFlags {
  uint face_flags[];
};
layout(std430, binding = BINDING_FACE_PAIR) writeonly buffer FacePairs {
  FacePair face_pairs[];
};

uniform uint u_pair_capacity;  // FacePair slots in SSBO 10

void flag_colliding_face(uint face) {
  if (atomicExchange(face_flags[face], 1u) == 0u) atomicAdd(counters.colliding_faces, 1u);
}

// Tests global faces face_a (of the mesh pair's mesh a) and face_b (of its mesh b) as the C++
// backend does (cpu_narrow_phase.h): only face_a < face_b, which within one mesh
// (self-collision) keeps one of the two orders the broad phases enumerate.
void test_face_pair(uint face_a, uint face_b) {
  if (face_a >= face_b) return;
  const TriTriResult r = face_pair_intersect(faces[face_a], faces[face_b]);
  if (!r.intersect) return;
  flag_colliding_face(face_a);
  flag_colliding_face(face_b);
  const uint slot = atomicAdd(counters.face_pairs, 1u);
  if (slot >= u_pair_capacity) return;  // counted: the host sees the overflow
  face_pairs[slot] = FacePair(face_a, face_b, r.coplanar ? 1u : 0u, 0u, vec4(r.segment0, 0.0),
                              vec4(r.segment1, 0.0));
}
