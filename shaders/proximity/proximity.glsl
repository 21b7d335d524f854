// Proximity candidates (issue 12), mirroring src/core/collision/proximity.h line for line:
// surface_neighbours, emit_if_within_reach and emit_face_pair_candidates (the vertices' side,
// reach_box and the swept corners, is proximity_vertices.glsl; the distances
// common/primitive_distance.glsl), with the same tests in the same order on the same floats,
// so that the GL search finds exactly the CPU's candidates (CpuProximity::find). Change both
// files together. (The C++ template's `wanted` filter is the CPU's widening's alone: a GL
// search keeps every candidate.)
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
// then fa's owned edges against fb's (fa and fb swept as sa and sb, their primitives' boxes pa
// and pb: sweep_face, sweep_primitives); each pair
// whose primitives' boxes overlap kept when its primitives can come within the sum of the two
// reaches.
void emit_face_pair_candidates(Face fa, SweptFace sa, SweptPrimitives pa, uint index_a,
                               uint owners_a, Face fb, SweptFace sb, SweptPrimitives pb,
                               uint index_b, uint owners_b) {
  for (uint k = 0u; k < 3u; ++k) {
    if ((owners_a & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(pa.vertex_box[k], sb.box)) {
      precise float reach = sa.reach[k] + sb.face_reach;
      emit_if_within_reach(ProximityCandidate(CONTACT_VERTEX_FACE, fa.body, fb.body, index_b,
                                              uvec4(face_corner(fa, k), fb.a, fb.b, fb.c)),
                           vec3[4](sa.x[k], sb.x[0], sb.x[1], sb.x[2]),
                           vec3[4](sa.x[3u + k], sb.x[3], sb.x[4], sb.x[5]), reach);
    }
  }
  for (uint k = 0u; k < 3u; ++k) {
    if ((owners_b & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(pb.vertex_box[k], sa.box)) {
      precise float reach = sb.reach[k] + sa.face_reach;
      emit_if_within_reach(ProximityCandidate(CONTACT_VERTEX_FACE, fb.body, fa.body, index_a,
                                              uvec4(face_corner(fb, k), fa.a, fa.b, fa.c)),
                           vec3[4](sb.x[k], sa.x[0], sa.x[1], sa.x[2]),
                           vec3[4](sb.x[3u + k], sa.x[3], sa.x[4], sa.x[5]), reach);
    }
  }
  // The owned edges' pairs, through the owner bits.
  for (uint ea = (owners_a / OWNS_EDGE0) & 7u; ea != 0u; ea &= ea - 1u) {
    const uint i = uint(findLSB(ea));
    const uint i1 = NEXT_CORNER[i];
    const float reach_a = proximity_max(sa.reach[i], sa.reach[i1]);
    for (uint eb = (owners_b / OWNS_EDGE0) & 7u; eb != 0u; eb &= eb - 1u) {
      const uint j = uint(findLSB(eb));
      if (boxes_overlap(pa.edge_box[i], pb.edge_box[j])) {
        const uint j1 = NEXT_CORNER[j];
        const float reach_b = proximity_max(sb.reach[j], sb.reach[j1]);
        precise float reach = reach_a + reach_b;
        emit_if_within_reach(
            ProximityCandidate(CONTACT_EDGE_EDGE, fa.body, fb.body, 0u,
                               uvec4(face_corner(fa, i), face_corner(fa, i1), face_corner(fb, j),
                                     face_corner(fb, j1))),
            vec3[4](sa.x[i], sa.x[i1], sb.x[j], sb.x[j1]),
            vec3[4](sa.x[3u + i], sa.x[3u + i1], sb.x[3u + j], sb.x[3u + j1]), reach);
      }
    }
  }
}
