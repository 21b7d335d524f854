// Narrow phase: triangle-triangle intersection after Moller 1997, mirroring
// src/core/collision/tri_tri_intersection.{h,cpp} line for line: the same constants, the same
// float operations in the same order, so that the GL and CPU backends take the same decisions.
// Change both files together. The why of every tolerance is in the .cpp.
//
// Every float that feeds a decision is `precise`: without it the driver may fuse a * b + c into
// one fma (one rounding instead of two) or reorder sums, and the answers near the uncertain zone
// would no longer match the C++ ones. dot and cross (common/exact_math.glsl) and length are
// written out for the same reason (and to fix glm's order of the sums: (x + y) + z).

#include "common/exact_math.glsl"

// kTriTriTolerance, kTriTriRoundoff, kTriTriDegenerateTolerance (tri_tri_intersection.h).
const float kTriTriTolerance = 1e-5;
const float kTriTriRoundoff = 1e-6;
const float kTriTriDegenerateTolerance = 1e-4;

// TriTriResult: segment0/segment1 are set only when intersect && !coplanar, else zero.
struct TriTriResult {
  bool intersect;
  bool coplanar;
  vec3 segment0;
  vec3 segment1;
};


// glm::length.
float tri_tri_length(vec3 v) {
  precise float r = sqrt(exact_dot(v, v));
  return r;
}

// longest_edge2.
float tri_tri_longest_edge2(vec3 t[3]) {
  precise vec3 e0 = t[1] - t[0];
  precise vec3 e1 = t[2] - t[1];
  precise vec3 e2 = t[0] - t[2];
  return max(exact_dot(e0, e0), max(exact_dot(e1, e1), exact_dot(e2, e2)));
}

// snap_to_zero.
float tri_tri_snap_to_zero(float v, float tolerance) {
  return abs(v) <= tolerance ? 0.0 : v;
}

// same_strict_side.
bool tri_tri_same_strict_side(float d[3]) {
  return (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0);
}

// same_strict_sign.
bool tri_tri_same_strict_sign(float a, float b) {
  return (a < 0.0 && b < 0.0) || (a > 0.0 && b > 0.0);
}

// opposite_signs.
bool tri_tri_opposite_signs(float a, float b) {
  return (a < 0.0 && b > 0.0) || (a > 0.0 && b < 0.0);
}

// LineInterval.
struct TriTriLineInterval {
  float t_min;
  float t_max;
  vec3 x_min;
  vec3 x_max;
  int edge_min;
  int edge_max;
};

// line_interval.
TriTriLineInterval tri_tri_line_interval(vec3 t[3], float d[3], vec3 dir, vec3 origin) {
  TriTriLineInterval r = TriTriLineInterval(3.4e38, -3.4e38, vec3(0.0), vec3(0.0), 0, 0);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    bool found = false;
    precise vec3 x = vec3(0.0);
    if (d[i] == 0.0) {
      x = t[i];
      found = true;
    } else if (tri_tri_opposite_signs(d[i], d[j])) {
      precise float f = d[i] / (d[i] - d[j]);  // d[i] != d[j]: no division by zero
      x = t[i] + (t[j] - t[i]) * f;
      found = true;
    }
    const float s = exact_dot(dir, x - origin);
    if (found && s < r.t_min) {
      r.t_min = s;
      r.x_min = x;
      r.edge_min = i;
    }
    if (found && s > r.t_max) {
      r.t_max = s;
      r.x_max = x;
      r.edge_max = i;
    }
  }
  return r;
}

// edge_axis_separates.
bool tri_tri_edge_axis_separates(vec3 a[3], vec3 b[3], int ea, int eb, float size) {
  const vec3 w = exact_cross(a[(ea + 1) % 3] - a[ea], b[(eb + 1) % 3] - b[eb]);
  float a_lo = 0.0;  // a[0] itself
  float a_hi = 0.0;
  float b_lo = 3.4e38;
  float b_hi = -3.4e38;
  for (int i = 0; i < 3; ++i) {
    const float pa = exact_dot(w, a[i] - a[0]);
    const float pb = exact_dot(w, b[i] - a[0]);
    a_lo = min(a_lo, pa);
    a_hi = max(a_hi, pa);
    b_lo = min(b_lo, pb);
    b_hi = max(b_hi, pb);
  }
  precise float margin = kTriTriTolerance * size * tri_tri_length(w);
  precise float gap_ab = b_lo - a_hi;
  precise float gap_ba = a_lo - b_hi;
  return gap_ab > margin || gap_ba > margin;
}

// orient2d.
float tri_tri_orient2d(vec2 a, vec2 b, vec2 c) {
  precise float r = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return r;
}

// within_extent_2d.
bool tri_tri_within_extent_2d(vec2 a, vec2 b, vec2 c, float length_tol) {
  precise float ab_x = b.x - a.x;
  precise float ab_y = b.y - a.y;
  const int k = abs(ab_x) >= abs(ab_y) ? 0 : 1;
  precise float lo = min(a[k], b[k]) - length_tol;
  precise float hi = max(a[k], b[k]) + length_tol;
  return lo <= c[k] && c[k] <= hi;
}

// segments_meet_2d.
bool tri_tri_segments_meet_2d(vec2 a, vec2 b, vec2 c, vec2 d, float area_tol, float length_tol) {
  const float r1 = tri_tri_orient2d(a, b, c);
  const float r2 = tri_tri_orient2d(a, b, d);
  const float r3 = tri_tri_orient2d(c, d, a);
  const float r4 = tri_tri_orient2d(c, d, b);
  const float o1 = tri_tri_snap_to_zero(r1, area_tol);
  const float o2 = tri_tri_snap_to_zero(r2, area_tol);
  const float o3 = tri_tri_snap_to_zero(r3, area_tol);
  const float o4 = tri_tri_snap_to_zero(r4, area_tol);
  if (o1 == 0.0 && o2 == 0.0) {  // collinear: overlap of the 1D intervals on ab's main axis
    precise float ab_x = b.x - a.x;
    precise float ab_y = b.y - a.y;
    const int k = abs(ab_x) >= abs(ab_y) ? 0 : 1;
    precise float hi = min(max(a[k], b[k]), max(c[k], d[k])) + length_tol;
    return max(min(a[k], b[k]), min(c[k], d[k])) <= hi;
  }
  // |r3|, |r4| > area_tol with opposite signs: no division by zero.
  if (tri_tri_opposite_signs(o3, o4)) {
    precise float f = r3 / (r3 - r4);
    precise vec2 x = a + (b - a) * f;
    return tri_tri_within_extent_2d(c, d, x, length_tol);
  }
  if (tri_tri_opposite_signs(o1, o2)) {
    precise float f = r1 / (r1 - r2);
    precise vec2 x = c + (d - c) * f;
    return tri_tri_within_extent_2d(a, b, x, length_tol);
  }
  return (o1 == 0.0 && tri_tri_within_extent_2d(a, b, c, length_tol)) ||
         (o2 == 0.0 && tri_tri_within_extent_2d(a, b, d, length_tol)) ||
         (o3 == 0.0 && tri_tri_within_extent_2d(c, d, a, length_tol)) ||
         (o4 == 0.0 && tri_tri_within_extent_2d(c, d, b, length_tol));
}

// point_in_triangle_2d.
bool tri_tri_point_in_triangle_2d(vec2 x, vec2 t[3], float area_tol) {
  const float s0 = tri_tri_snap_to_zero(tri_tri_orient2d(t[0], t[1], x), area_tol);
  const float s1 = tri_tri_snap_to_zero(tri_tri_orient2d(t[1], t[2], x), area_tol);
  const float s2 = tri_tri_snap_to_zero(tri_tri_orient2d(t[2], t[0], x), area_tol);
  const bool has_negative = s0 < 0.0 || s1 < 0.0 || s2 < 0.0;
  const bool has_positive = s0 > 0.0 || s1 > 0.0 || s2 > 0.0;
  return !(has_negative && has_positive);
}

// projection_axes.
void tri_tri_projection_axes(vec3 n, out int u, out int v) {
  const vec3 m = abs(n);
  u = 1;  // drop x
  v = 2;
  if (m.y >= m.x && m.y >= m.z) {  // drop y
    u = 0;
    v = 2;
  } else if (m.z >= m.x && m.z >= m.y) {  // drop z
    u = 0;
    v = 1;
  }
}

// The projection of segment_in_plane_meets_triangle: x relative to origin, coordinates u, v.
vec2 tri_tri_project(vec3 x, vec3 origin, int u, int v) {
  precise vec2 r = vec2(x[u] - origin[u], x[v] - origin[v]);
  return r;
}

// segment_in_plane_meets_triangle.
bool tri_tri_segment_in_plane_meets_triangle(vec3 s0, vec3 s1, vec3 t[3], vec3 n, float size) {
  int u = 0;
  int v = 0;
  tri_tri_projection_axes(n, u, v);
  vec2 t2[3] = vec2[3](tri_tri_project(t[0], t[0], u, v), tri_tri_project(t[1], t[0], u, v),
                       tri_tri_project(t[2], t[0], u, v));
  const vec2 a = tri_tri_project(s0, t[0], u, v);
  const vec2 b = tri_tri_project(s1, t[0], u, v);
  precise float area_tol = kTriTriTolerance * size * size;
  precise float length_tol = kTriTriTolerance * size;
  if (tri_tri_point_in_triangle_2d(a, t2, area_tol) || tri_tri_point_in_triangle_2d(b, t2, area_tol)) {
    return true;
  }
  precise vec2 ab = b - a;
  precise float ab2 = ab.x * ab.x + ab.y * ab.y;
  precise float length_tol2 = length_tol * length_tol;
  if (!(ab2 > length_tol2)) return false;
  bool meet = false;
  for (int i = 0; i < 3; ++i) {
    meet = meet || tri_tri_segments_meet_2d(a, b, t2[i], t2[(i + 1) % 3], area_tol, length_tol);
  }
  return meet;
}

// coplanar_overlap.
bool tri_tri_coplanar_overlap(vec3 a[3], vec3 b[3], vec3 n, float size) {
  int u = 0;
  int v = 0;
  tri_tri_projection_axes(n, u, v);
  precise vec2 a2[3];
  precise vec2 b2[3];
  for (int i = 0; i < 3; ++i) {  // relative to a[0]: keeps the projected values small
    a2[i] = vec2(a[i][u] - a[0][u], a[i][v] - a[0][v]);
    b2[i] = vec2(b[i][u] - a[0][u], b[i][v] - a[0][v]);
  }
  precise float area_tol = kTriTriTolerance * size * size;
  precise float length_tol = kTriTriTolerance * size;
  bool meet = false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      meet = meet || tri_tri_segments_meet_2d(a2[i], a2[(i + 1) % 3], b2[j], b2[(j + 1) % 3],
                                              area_tol, length_tol);
    }
  }
  return meet || tri_tri_point_in_triangle_2d(a2[0], b2, area_tol) ||
         tri_tri_point_in_triangle_2d(b2[0], a2, area_tol);
}

// slab_part_meets_triangle: whether a point of s within tol of t's plane (normal n, unit u)
// lies, projected where n is largest, on t within the 2D tolerances (see the C++ for the why).
bool tri_tri_slab_part_meets_triangle(vec3 s[3], vec3 t[3], vec3 n, vec3 u, float tol, float size,
                                      out vec3 contact) {
  contact = vec3(0.0);
  vec3 poly[5];
  float dist[5];
  int count = 3;
  for (int i = 0; i < 3; ++i) {
    poly[i] = s[i];
    dist[i] = exact_dot(u, s[i] - t[0]);
  }
  for (int side = 0; side < 2; ++side) {  // clip by dist <= tol, then by -dist <= tol
    const float side_sign = side == 0 ? 1.0 : -1.0;
    vec3 out_poly[5];
    float out_dist[5];
    int out_count = 0;
    for (int i = 0; i < count; ++i) {
      const int j = (i + 1) % count;
      precise float fi = side_sign * dist[i] - tol;
      precise float fj = side_sign * dist[j] - tol;
      if (fi <= 0.0) {
        out_poly[out_count] = poly[i];
        out_dist[out_count] = dist[i];
        ++out_count;
      }
      if (tri_tri_opposite_signs(fi, fj)) {  // fi != fj: no division by zero
        precise float f = fi / (fi - fj);
        precise vec3 x = poly[i] + (poly[j] - poly[i]) * f;
        precise float d = dist[i] + (dist[j] - dist[i]) * f;
        out_poly[out_count] = x;
        out_dist[out_count] = d;
        ++out_count;
      }
    }
    for (int i = 0; i < out_count; ++i) {
      poly[i] = out_poly[i];
      dist[i] = out_dist[i];
    }
    count = out_count;
  }
  if (count == 0) return false;
  int pu = 0;
  int pv = 0;
  tri_tri_projection_axes(n, pu, pv);
  vec2 t2[3] = vec2[3](tri_tri_project(t[0], t[0], pu, pv), tri_tri_project(t[1], t[0], pu, pv),
                       tri_tri_project(t[2], t[0], pu, pv));
  vec2 p2[5];
  for (int i = 0; i < count; ++i) {
    p2[i] = tri_tri_project(poly[i], t[0], pu, pv);
  }
  precise float area_tol = kTriTriTolerance * size * size;
  precise float length_tol = kTriTriTolerance * size;
  // The first witness found is the contact.
  bool meet = false;
  for (int i = 0; i < count; ++i) {
    if (!meet && tri_tri_point_in_triangle_2d(p2[i], t2, area_tol)) {
      meet = true;
      contact = poly[i];
    }
    // A proper crossing of the polygon's edge i and an edge of t, by the signs.
    const int j = (i + 1) % count;
    for (int k = 0; k < 3; ++k) {
      const vec2 a = t2[k];
      const vec2 b = t2[(k + 1) % 3];
      const float r1 = tri_tri_orient2d(a, b, p2[i]);
      const float r2 = tri_tri_orient2d(a, b, p2[j]);
      if (!meet && tri_tri_opposite_signs(r1, r2) &&
          tri_tri_opposite_signs(tri_tri_orient2d(p2[i], p2[j], a), tri_tri_orient2d(p2[i], p2[j], b))) {
        meet = true;
        precise float f = r1 / (r1 - r2);  // r1 != r2
        precise vec3 x = poly[i] + (poly[j] - poly[i]) * f;
        contact = x;
      }
    }
  }
  // t's vertex within length_tol of the inner side of every edge's line.
  // And within the polygon's bounding box (grown by length_tol).
  precise float area2 = 0.0;
  for (int i = 1; i + 1 < count; ++i) {
    area2 += tri_tri_orient2d(p2[0], p2[i], p2[i + 1]);
  }
  vec2 lo = p2[0];
  vec2 hi = p2[0];
  for (int i = 1; i < count; ++i) {
    lo = min(lo, p2[i]);
    hi = max(hi, p2[i]);
  }
  precise float lo_x = lo.x - length_tol;
  precise float hi_x = hi.x + length_tol;
  precise float lo_y = lo.y - length_tol;
  precise float hi_y = hi.y + length_tol;
  bool inside = lo_x <= t2[0].x && t2[0].x <= hi_x && lo_y <= t2[0].y && t2[0].y <= hi_y;
  for (int i = 0; i < count; ++i) {
    const int j = (i + 1) % count;
    precise vec2 e = p2[j] - p2[i];
    const float r = tri_tri_orient2d(p2[i], p2[j], t2[0]);
    precise float o = area2 > 0.0 ? r : -r;
    precise float e2 = e.x * e.x + e.y * e.y;
    precise float bound = length_tol * length_tol * e2;
    precise float o2 = o * o;
    inside = inside && !(o < 0.0 && o2 > bound);
  }
  if (!meet && inside) {
    meet = true;
    contact = t[0];
  }
  return meet;
}

// tri_tri_intersect: intersection of triangles p and q, symmetric in p and q.
// Whether the closed bounding boxes of p and q share a point (exact: min/max do not round).
bool tri_tri_boxes_touch(vec3 p[3], vec3 q[3]) {
  vec3 p_min = min(min(p[0], p[1]), p[2]);
  vec3 p_max = max(max(p[0], p[1]), p[2]);
  vec3 q_min = min(min(q[0], q[1]), q[2]);
  vec3 q_max = max(max(q[0], q[1]), q[2]);
  return all(lessThanEqual(p_min, q_max)) && all(lessThanEqual(q_min, p_max));
}

TriTriResult tri_tri_intersect(vec3 p[3], vec3 q[3]) {
  TriTriResult result = TriTriResult(false, false, vec3(0.0), vec3(0.0));
  // Triangles whose bounding boxes are apart cannot meet (see the C++ for why this matters to
  // the broad phases).
  if (!tri_tri_boxes_touch(p, q)) return result;
  // Symmetry: process the pair in a canonical order (lexicographic on the 9 coordinates).
  bool swap = false;
  bool decided = false;
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) {
      if (!decided && p[k][c] != q[k][c]) {
        swap = q[k][c] < p[k][c];
        decided = true;
      }
    }
  }
  vec3 a[3];
  vec3 b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = swap ? q[i] : p[i];
    b[i] = swap ? p[i] : q[i];
  }

  // Degenerate triangles have no plane: no intersection.
  const float la2 = tri_tri_longest_edge2(a);
  const float lb2 = tri_tri_longest_edge2(b);
  const vec3 na = exact_cross(a[1] - a[0], a[2] - a[0]);
  const float na_len = tri_tri_length(na);
  precise float degenerate_a = kTriTriDegenerateTolerance * la2;
  if (!(na_len > degenerate_a)) return result;
  precise float size = sqrt(max(la2, lb2));
  precise vec3 ua = na / na_len;

  // Signed distances of each triangle's vertices to the other's plane, snapped to the plane.
  precise float tol_a = (kTriTriTolerance + kTriTriRoundoff * la2 / na_len) * size;
  float db[3];
  for (int i = 0; i < 3; ++i) {
    db[i] = tri_tri_snap_to_zero(exact_dot(ua, b[i] - a[0]), tol_a);
  }
  // b wholly on one side of a's plane beyond the tolerance: apart (see the C++).
  if (tri_tri_same_strict_side(db)) return result;
  const vec3 nb = exact_cross(b[1] - b[0], b[2] - b[0]);
  const float nb_len = tri_tri_length(nb);
  precise float degenerate_b = kTriTriDegenerateTolerance * lb2;
  if (!(nb_len > degenerate_b)) return result;
  precise vec3 ub = nb / nb_len;
  precise float tol_b = (kTriTriTolerance + kTriTriRoundoff * lb2 / nb_len) * size;
  float da[3];
  for (int i = 0; i < 3; ++i) {
    da[i] = tri_tri_snap_to_zero(exact_dot(ub, a[i] - b[0]), tol_b);
  }
  const bool b_on_plane_a = db[0] == 0.0 && db[1] == 0.0 && db[2] == 0.0;
  const bool a_on_plane_b = da[0] == 0.0 && da[1] == 0.0 && da[2] == 0.0;
  if (b_on_plane_a || a_on_plane_b) {
    result.coplanar = true;
    result.intersect = tri_tri_coplanar_overlap(a, b, na, size);
    return result;
  }
  if (tri_tri_same_strict_side(da)) return result;

  // Both triangles cross the line of the planes' intersection: overlap of their intervals.
  const vec3 dir = exact_cross(ua, ub);
  const TriTriLineInterval ia = tri_tri_line_interval(a, da, dir, a[0]);
  const TriTriLineInterval ib = tri_tri_line_interval(b, db, dir, a[0]);
  const bool lo_from_a = ia.t_min >= ib.t_min;
  const bool hi_from_a = ia.t_max <= ib.t_max;
  const float t_lo = lo_from_a ? ia.t_min : ib.t_min;
  const float t_hi = hi_from_a ? ia.t_max : ib.t_max;
  const vec3 x_lo = lo_from_a ? ia.x_min : ib.x_min;
  const vec3 x_hi = hi_from_a ? ia.x_max : ib.x_max;
  precise float gap_tol = kTriTriTolerance * size * tri_tri_length(dir);
  precise float t_hi_closed = t_hi + gap_tol;
  const bool gap = t_lo > t_hi_closed;
  // A vertex snapped onto the other plane may lie up to tolerance / sin(angle) from the planes'
  // line: each triangle's part on the other's plane must meet the other triangle there, in 2D.
  const bool snapped = da[0] == 0.0 || da[1] == 0.0 || da[2] == 0.0 || db[0] == 0.0 ||
                       db[1] == 0.0 || db[2] == 0.0;
  // b's part against a, then a's against b (one call site: llvmpipe compiles each call in full).
  bool missed_in_plane = false;
  for (int k = 0; !gap && snapped && !missed_in_plane && k < 2; ++k) {
    vec3 t[3];
    if (k == 0) {
      t = a;
    } else {
      t = b;
    }
    const vec3 s0 = k == 0 ? ib.x_min : ia.x_min;
    const vec3 s1 = k == 0 ? ib.x_max : ia.x_max;
    missed_in_plane = !tri_tri_segment_in_plane_meets_triangle(s0, s1, t, k == 0 ? na : nb, size);
  }
  if (!gap && !missed_in_plane) {
    result.intersect = true;
    const bool touching = t_lo > t_hi;  // a gap inside the tolerance: one contact point
    precise vec3 mid = 0.5 * (x_lo + x_hi);
    result.segment0 = touching ? mid : x_lo;
    result.segment1 = touching ? mid : x_hi;
    return result;
  }

  // A gap between the intervals: the axis across the two edges that make its facing ends (see
  // the C++).
  if (gap) {
    const bool a_first = ia.t_max < ib.t_min;
    if (tri_tri_edge_axis_separates(a, b, a_first ? ia.edge_max : ia.edge_min,
                                    a_first ? ib.edge_min : ib.edge_max, size)) {
      return result;
    }
  }

  // "Apart" not proven yet (see the C++): apart only when, for one of the two triangles, no
  // point of the other within the plane tolerance of its plane lies over it.
  vec3 contact = vec3(0.0);
  for (int k = 0; k < 2; ++k) {
    vec3 t[3];
    vec3 s[3];
    if (k == 0) {
      t = a;
      s = b;
    } else {
      t = b;
      s = a;
    }
    const float l2 = k == 0 ? la2 : lb2;
    const float n_len = k == 0 ? na_len : nb_len;
    precise float tol = (0.5 * kTriTriTolerance + kTriTriRoundoff * l2 / n_len) * size;
    vec3 x = vec3(0.0);
    if (!tri_tri_slab_part_meets_triangle(s, t, k == 0 ? na : nb, k == 0 ? ua : ub, tol, size, x)) {
      return result;
    }
    if (k == 0) contact = x;
  }
  result.intersect = true;
  result.segment0 = contact;
  result.segment1 = contact;
  return result;
}
