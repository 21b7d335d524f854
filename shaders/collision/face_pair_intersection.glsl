// The narrow phase of one pair of surface faces by their nodes, mirroring
// src/core/collision/face_pair_intersection.{h,cpp} line for line (the why is there): faces
// sharing an edge are never a contact; faces sharing one node are when the edge opposite it of
// one meets the other; faces sharing no node take tri_tri_intersect. Change both together.
// The same operations on the same values as the C++, but each costly function called from one
// place (tri_tri_intersect_sharing_vertex folded into face_pair_intersect, loops over the two
// directions): llvmpipe compiles every call in full and runs divergent branches under a mask,
// so each extra copy slows every invocation (GL brute force, phase 2: 880 -> 500 ms a frame).
#include "collision/surface.glsl"
#include "collision/tri_tri_intersection.glsl"
#include "common/layout.glsl"

// SharedNodes: how many vertices faces a and b share, and the corner of the first in each.
struct SharedNodes {
  int count;
  int corner_a;
  int corner_b;
};

uint face_corner(Face f, int i) {
  return i == 0 ? f.a : (i == 1 ? f.b : f.c);
}

SharedNodes shared_nodes(Face a, Face b) {
  SharedNodes s = SharedNodes(0, 0, 0);
  // Vertex indices are local to a mesh: faces of different meshes share none.
  if (a.body != b.body) return s;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (face_corner(a, i) != face_corner(b, j)) continue;
      if (s.count == 0) {
        s.corner_a = i;
        s.corner_b = j;
      }
      ++s.count;
    }
  }
  return s;
}

// segment_triangle_meet.
bool segment_triangle_meet(vec3 s0, vec3 s1, vec3 t[3]) {
  const float l2 = tri_tri_longest_edge2(t);
  const vec3 n = exact_cross(t[1] - t[0], t[2] - t[0]);
  const float n_len = tri_tri_length(n);
  precise float degenerate = kTriTriDegenerateTolerance * l2;
  if (!(n_len > degenerate)) return false;
  precise vec3 e = s1 - s0;
  precise float size = sqrt(max(l2, exact_dot(e, e)));
  precise vec3 u = n / n_len;
  precise float tol = (kTriTriTolerance + kTriTriRoundoff * l2 / n_len) * size;
  const float d0 = tri_tri_snap_to_zero(exact_dot(u, s0 - t[0]), tol);
  const float d1 = tri_tri_snap_to_zero(exact_dot(u, s1 - t[0]), tol);
  if (tri_tri_same_strict_sign(d0, d1)) return false;

  // On the plane: both ends (crossing an edge, or wholly inside), else the one point on it, an
  // end or the crossing (d0 != d1 there). One call: llvmpipe compiles each call in full.
  vec3 x0 = s0;
  vec3 x1 = s1;
  if (d0 != 0.0 || d1 != 0.0) {
    precise float f = d0 / (d0 - d1);
    precise vec3 crossing = s0 + e * f;
    x0 = d0 == 0.0 ? s0 : (d1 == 0.0 ? s1 : crossing);
    x1 = x0;
  }
  return tri_tri_segment_in_plane_meets_triangle(x0, x1, t, n, size);
}

// Corner `first + i` (mod 3) of face f, for i = 0, 1, 2: load_rotated.
vec3[3] load_rotated(Face f, int first) {
  const uvec2 at = vertex_layout(f.body);
  return vec3[3](vertex_at(at, face_corner(f, first)),
                 vertex_at(at, face_corner(f, (first + 1) % 3)),
                 vertex_at(at, face_corner(f, (first + 2) % 3)));
}

// face_pair_intersect, reading the positions with vertex_position (collision/surface.glsl).
TriTriResult face_pair_intersect(Face fa, Face fb) {
  const TriTriResult none = TriTriResult(false, false, vec3(0.0), vec3(0.0));
  // face_vertices: corners a, b, c.
  vec3 p[3] = load_rotated(fa, 0);
  vec3 q[3] = load_rotated(fb, 0);
  // The exact box test first (most pairs): faces sharing a node have touching boxes.
  if (!tri_tri_boxes_touch(p, q)) return none;
  const SharedNodes common_nodes = shared_nodes(fa, fb);
  if (common_nodes.count >= 2) return none;
  if (common_nodes.count == 1) {
    const int a0 = common_nodes.corner_a;
    const int b0 = common_nodes.corner_b;
    p = load_rotated(fa, a0);
    q = load_rotated(fb, b0);
    // p's opposite edge against q, then q's against p, from one call site.
    bool meet = false;
    for (int k = 0; k < 2 && !meet; ++k) {
      vec3 t[3];
      if (k == 0) {
        t = q;
      } else {
        t = p;
      }
      meet = segment_triangle_meet(k == 0 ? p[1] : q[1], k == 0 ? p[2] : q[2], t);
    }
    if (!meet) return none;
  }
  // One call site of tri_tri_intersect (tri_tri_intersect_sharing_vertex inlined): llvmpipe
  // compiles each call in full, and a second copy made brute force 3x slower.
  return tri_tri_intersect(p, q);
}
