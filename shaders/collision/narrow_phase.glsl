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
#include "collision/surface.glsl"
#include "collision/tri_tri_intersection.glsl"
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

// Tests global faces face_a (of the body pair's body a) and face_b (of its body b), p and q in
// the vertex order a, b, c as the C++ backend passes them.
void test_face_pair(uint face_a, uint face_b) {
  const Face fa = faces[face_a];
  const Face fb = faces[face_b];
  vec3 p[3] = vec3[3](positions[fa.a].xyz, positions[fa.b].xyz, positions[fa.c].xyz);
  vec3 q[3] = vec3[3](positions[fb.a].xyz, positions[fb.b].xyz, positions[fb.c].xyz);
  const TriTriResult r = tri_tri_intersect(p, q);
  if (!r.intersect) return;
  flag_colliding_face(face_a);
  flag_colliding_face(face_b);
  const uint slot = atomicAdd(counters.face_pairs, 1u);
  if (slot >= u_pair_capacity) return;  // counted: the host sees the overflow
  face_pairs[slot] = FacePair(face_a, face_b, r.coplanar ? 1u : 0u, 0u, vec4(r.segment0, 0.0),
                              vec4(r.segment1, 0.0));
}
