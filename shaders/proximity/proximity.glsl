// Proximity candidates (issue 12), mirroring src/core/collision/proximity.h line for line:
// reach_box, faces_share_vertex and emit_face_pair_candidates, with the same tests in the same
// order, so that the GL search finds exactly the CPU's candidates (CpuProximity::find). Change
// both files together. Only comparisons and exact min / max / +- reach happen here; the one
// rounding operation, the sum of the two meshes' reaches, is done once in the including shader
// as in the C++.
//
// An including shader must define
//   void proximity_emit(ProximityCandidate c);
// (the C++ template's `emit`): called for each candidate of a face pair, in the C++ order.
#include "collision/broad_phase.glsl"
#include "collision/surface.glsl"
#include "common/layout.glsl"
#include "proximity/proximity_buffers.glsl"

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

// glm::min / glm::max per component (b < a ? b : a, a < b ? b : a).
vec3 proximity_min(vec3 a, vec3 b) {
  return vec3(b.x < a.x ? b.x : a.x, b.y < a.y ? b.y : a.y, b.z < a.z ? b.z : a.z);
}
vec3 proximity_max(vec3 a, vec3 b) {
  return vec3(a.x < b.x ? b.x : a.x, a.y < b.y ? b.y : a.y, a.z < b.z ? b.z : a.z);
}

// reach_box of one point, of a segment, of a triangle.
Box reach_box1(vec3 p, float reach) {
  return Box(vec4(p - reach, 0.0), vec4(p + reach, 0.0));
}
Box reach_box2(vec3 p0, vec3 p1, float reach) {
  const vec3 lo = proximity_min(p0, p1), hi = proximity_max(p0, p1);
  return Box(vec4(lo - reach, 0.0), vec4(hi + reach, 0.0));
}
Box reach_box3(vec3 p[3], float reach) {
  vec3 lo = p[0], hi = p[0];
  for (uint i = 1u; i < 3u; ++i) {
    lo = proximity_min(lo, p[i]);
    hi = proximity_max(hi, p[i]);
  }
  return Box(vec4(lo - reach, 0.0), vec4(hi + reach, 0.0));
}

// collision::face_corner.
uint face_corner(Face f, uint k) { return k == 0u ? f.a : (k == 1u ? f.b : f.c); }

// sweep_box: the box and the box moved by d (glm::min / glm::max written out, componentwise).
Box sweep_box(Box box, vec3 d) {
  const vec3 lo = vec3(0.0 < d.x ? 0.0 : d.x, 0.0 < d.y ? 0.0 : d.y, 0.0 < d.z ? 0.0 : d.z);
  const vec3 hi = vec3(d.x < 0.0 ? 0.0 : d.x, d.y < 0.0 ? 0.0 : d.y, d.z < 0.0 ? 0.0 : d.z);
  return Box(vec4(box.min.xyz + lo, 0.0), vec4(box.max.xyz + hi, 0.0));
}

// faces_share_vertex.
bool faces_share_vertex(Face a, Face b) {
  for (uint i = 0u; i < 3u; ++i) {
    const uint v = face_corner(a, i);
    if (v == b.a || v == b.b || v == b.c) return true;
  }
  return false;
}

// emit_face_pair_candidates: fa's owned vertices against fb, fb's owned vertices against fa,
// then fa's owned edges against fb's.
void emit_face_pair_candidates(Face fa, uint index_a, uint owners_a, Face fb, uint index_b,
                               uint owners_b, float reach, vec3 sweep) {
  vec3 xa[3], xb[3];
  xa[0] = vertex_position(fa.body, fa.a);
  xa[1] = vertex_position(fa.body, fa.b);
  xa[2] = vertex_position(fa.body, fa.c);
  xb[0] = vertex_position(fb.body, fb.a);
  xb[1] = vertex_position(fb.body, fb.b);
  xb[2] = vertex_position(fb.body, fb.c);
  const Box box_a = reach_box3(xa, 0.0);
  const Box box_b = reach_box3(xb, 0.0);
  for (uint k = 0u; k < 3u; ++k) {
    if ((owners_a & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(sweep_box(reach_box1(xa[k], reach), sweep), box_b))
      proximity_emit(ProximityCandidate(CONTACT_VERTEX_FACE, fa.body, fb.body, index_b,
                                        uvec4(face_corner(fa, k), fb.a, fb.b, fb.c)));
  }
  for (uint k = 0u; k < 3u; ++k) {
    if ((owners_b & (OWNS_VERTEX0 << k)) != 0u && boxes_overlap(sweep_box(reach_box1(xb[k], reach), -sweep), box_a))
      proximity_emit(ProximityCandidate(CONTACT_VERTEX_FACE, fb.body, fa.body, index_a,
                                        uvec4(face_corner(fb, k), fa.a, fa.b, fa.c)));
  }
  for (uint i = 0u; i < 3u; ++i) {
    if ((owners_a & (OWNS_EDGE0 << i)) == 0u) continue;
    const Box grown = sweep_box(reach_box2(xa[i], xa[(i + 1u) % 3u], reach), sweep);
    for (uint j = 0u; j < 3u; ++j) {
      if ((owners_b & (OWNS_EDGE0 << j)) == 0u) continue;
      if (boxes_overlap(grown, reach_box2(xb[j], xb[(j + 1u) % 3u], 0.0)))
        proximity_emit(ProximityCandidate(
            CONTACT_EDGE_EDGE, fa.body, fb.body, 0u,
            uvec4(face_corner(fa, i), face_corner(fa, (i + 1u) % 3u), face_corner(fb, j),
                  face_corner(fb, (j + 1u) % 3u))));
    }
  }
}
