// Proximity candidates (issue 12), mirroring src/core/collision/proximity.h line for line:
// surface_neighbours, emit_if_within_reach and emit_face_pair_candidates (the vertices' side,
// reach_box and the swept corners, is proximity_vertices.glsl; the distances
// common/primitive_distance.glsl), with the same tests in the same order on the same floats,
// so that the GL search finds exactly the CPU's candidates (CpuProximity::find). Change both
// files together.
//
// An including shader must define
//   void proximity_emit(ProximityCandidate c);
// (the C++ template's `emit`): called for each candidate of a face pair, in the C++ order.
#include "collision/broad_phase.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"
#include "common/primitive_distance.glsl"
#include "proximity/proximity_buffers.glsl"
#include "proximity/proximity_vertices.glsl"

// 32 bytes. collision::ProximityCandidate: kind (CONTACT_VERTEX_FACE or CONTACT_EDGE_EDGE),
// the meshes, face_b (vertex-face: the face's index in the layout; else 0), the vertices
// (local to their meshes).
struct ProximityCandidate {
  uint kind;
  uint mesh_a;
  uint mesh_b;
  uint face_b;
  uvec4 vertices;
};

// collision::kOwnsVertex0, kOwnsEdge0: a face's owner bits (bit k: corner k, bit 3 + k: edge k
// from corner k to corner (k + 1) % 3).
#define OWNS_VERTEX0 1u
#define OWNS_EDGE0 8u

void proximity_emit(ProximityCandidate c);

// surface_neighbours: a vertex with a face it is a corner of, or two edges sharing a vertex, of
// one mesh.
bool surface_neighbours(ProximityCandidate c) {
  const uvec4 v = c.vertices;
  if (c.mesh_a != c.mesh_b) return false;
  if (c.kind == CONTACT_VERTEX_FACE) return v[0] == v[1] || v[0] == v[2] || v[0] == v[3];
  return v[0] == v[2] || v[0] == v[3] || v[1] == v[2] || v[1] == v[3];
}

// emit_if_within_reach: emits c unless its primitives are surface neighbours or their distance
// at x, less what their motion (x to end) can close of it, exceeds `reach`.
void emit_if_within_reach(ProximityCandidate c, vec3 x[4], vec3 end[4], float reach) {
  if (surface_neighbours(c)) return;
  precise vec3 m0 = end[0] - x[0], m1 = end[1] - x[1], m2 = end[2] - x[2], m3 = end[3] - x[3];
  const vec3 motion[4] = vec3[4](m0, m1, m2, m3);
  if (primitives_within(c.kind, x, closing_speed(c.kind, motion), reach)) proximity_emit(c);
}

// emit_face_pair_candidates: fa's owned vertices against fb, fb's owned vertices against fa,
// then fa's owned edges against fb's; each primitive's box swept along its vertices' paths and
// grown by its reach, each pair whose boxes overlap kept when its primitives can come within
// the sum of the two reaches.
void emit_face_pair_candidates(Face fa, uint index_a, uint owners_a, Face fb, uint index_b,
                               uint owners_b) {
  vec3 xa[6], xb[6];
  swept_face_vertices(fa, xa);
  swept_face_vertices(fb, xb);
  float ra[3], rb[3];
  const float face_a = face_reaches(fa, ra);
  const float face_b = face_reaches(fb, rb);
  const Box box_a = reach_box6(xa, face_a);
  const Box box_b = reach_box6(xb, face_b);
  for (uint k = 0u; k < 3u; ++k) {
    const vec3 path[2] = vec3[2](xa[k], xa[3u + k]);
    if ((owners_a & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(reach_box2(path, ra[k]), box_b)) {
      precise float reach = ra[k] + face_b;
      emit_if_within_reach(ProximityCandidate(CONTACT_VERTEX_FACE, fa.body, fb.body, index_b,
                                              uvec4(face_corner(fa, k), fb.a, fb.b, fb.c)),
                           vec3[4](xa[k], xb[0], xb[1], xb[2]),
                           vec3[4](xa[3u + k], xb[3], xb[4], xb[5]), reach);
    }
  }
  for (uint k = 0u; k < 3u; ++k) {
    const vec3 path[2] = vec3[2](xb[k], xb[3u + k]);
    if ((owners_b & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(reach_box2(path, rb[k]), box_a)) {
      precise float reach = rb[k] + face_a;
      emit_if_within_reach(ProximityCandidate(CONTACT_VERTEX_FACE, fb.body, fa.body, index_a,
                                              uvec4(face_corner(fb, k), fa.a, fa.b, fa.c)),
                           vec3[4](xb[k], xa[0], xa[1], xa[2]),
                           vec3[4](xb[3u + k], xa[3], xa[4], xa[5]), reach);
    }
  }
  for (uint i = 0u; i < 3u; ++i) {
    if ((owners_a & (OWNS_EDGE0 << i)) == 0u) continue;
    const uint i1 = (i + 1u) % 3u;
    const vec3 edge_a[4] = vec3[4](xa[i], xa[i1], xa[3u + i], xa[3u + i1]);
    const float reach_a = proximity_max(ra[i], ra[i1]);
    const Box grown = reach_box4(edge_a, reach_a);
    for (uint j = 0u; j < 3u; ++j) {
      if ((owners_b & (OWNS_EDGE0 << j)) == 0u) continue;
      const uint j1 = (j + 1u) % 3u;
      const vec3 edge_b[4] = vec3[4](xb[j], xb[j1], xb[3u + j], xb[3u + j1]);
      const float reach_b = proximity_max(rb[j], rb[j1]);
      if (boxes_overlap(grown, reach_box4(edge_b, reach_b))) {
        precise float reach = reach_a + reach_b;
        emit_if_within_reach(
            ProximityCandidate(CONTACT_EDGE_EDGE, fa.body, fb.body, 0u,
                               uvec4(face_corner(fa, i), face_corner(fa, i1), face_corner(fb, j),
                                     face_corner(fb, j1))),
            vec3[4](xa[i], xa[i1], xb[j], xb[j1]),
            vec3[4](xa[3u + i], xa[3u + i1], xb[3u + j], xb[3u + j1]), reach);
      }
    }
  }
}
