#include "collision/tri_tri_intersection.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "collision/tri_tri_primitives.h"

// Tolerances and the uncertain zone. Nothing is compared with an absolute epsilon: every
// tolerance is a dimensionless constant times the pair's own lengths, so scaling the pair scales
// the decision with it (the reference code's 1e-6 on plane distances fails at mm and km scales).
// The plane test |dot(n, x - a0)| with n = cross(e1, e2) snaps to zero within
// kTriTriTolerance |n| S + kTriTriRoundoff L^2 S (L the triangle's longest edge, S the pair's):
// the first term is the 1e-5 relative band asked of touching, the second the float error of the
// test itself, a few ulps of |e1| |e2| |x - a0|, which does not shrink with |n| and so dominates
// for slivers (below a height of ~1e-4 of the length the triangle counts as degenerate, since
// then the band would swallow everything near it). Every test snaps values inside its
// tolerance to zero, so a pair within ~1e-5 relative of touching is decided as touching, and
// touching counts as intersecting (a contact is better reported than missed; the response sees
// a zero-length segment). Distances are taken along unit normals so that values scale as L, not
// L^5 (mm to km scales stay far from float underflow and overflow, also on GPUs that flush
// denormals). Positions far from the origin relative to S (|x| / S > ~100) add input rounding
// the tolerance does not cover; callers should keep coordinates body- or scene-local.

namespace deformcd::collision {
namespace {

using namespace detail;

// The part of triangle t on the other triangle's plane, as an interval of the parameter
// dot(dir, x - origin) along the planes' intersection line, with the points at its ends. The
// points are its vertices on the plane (d == 0) and its edges' crossings of the plane.
struct LineInterval {
  float t_min;
  float t_max;
  glm::vec3 x_min;
  glm::vec3 x_max;
};

LineInterval line_interval(const glm::vec3 t[3], const float d[3], const glm::vec3& dir,
                           const glm::vec3& origin) {
  LineInterval r{3.4e38f, -3.4e38f, glm::vec3(0.0f), glm::vec3(0.0f)};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    bool found = false;
    glm::vec3 x(0.0f);
    if (d[i] == 0.0f) {
      x = t[i];
      found = true;
    } else if (opposite_signs(d[i], d[j])) {
      x = t[i] + (t[j] - t[i]) * (d[i] / (d[i] - d[j]));  // d[i] != d[j]: no division by zero
      found = true;
    }
    const float s = glm::dot(dir, x - origin);
    if (found && s < r.t_min) {
      r.t_min = s;
      r.x_min = x;
    }
    if (found && s > r.t_max) {
      r.t_max = s;
      r.x_max = x;
    }
  }
  return r;
}

// Coplanar triangles: project onto the coordinate plane where the normal n is largest, then
// edge-edge crossings, then containment.
bool coplanar_overlap(const glm::vec3 a[3], const glm::vec3 b[3], const glm::vec3& n, float size) {
  int u = 0;
  int v = 0;
  projection_axes(n, u, v);
  glm::vec2 a2[3];
  glm::vec2 b2[3];
  for (int i = 0; i < 3; ++i) {  // relative to a[0]: keeps the projected values small
    a2[i] = glm::vec2(a[i][u] - a[0][u], a[i][v] - a[0][v]);
    b2[i] = glm::vec2(b[i][u] - a[0][u], b[i][v] - a[0][v]);
  }
  const float area_tol = kTriTriTolerance * size * size;
  const float length_tol = kTriTriTolerance * size;
  bool meet = false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      meet = meet ||
             segments_meet_2d(a2[i], a2[(i + 1) % 3], b2[j], b2[(j + 1) % 3], area_tol, length_tol);
    }
  }
  return meet || point_in_triangle_2d(a2[0], b2, area_tol) ||
         point_in_triangle_2d(b2[0], a2, area_tol);
}

}  // namespace

TriTriResult tri_tri_intersect(const glm::vec3 p[3], const glm::vec3 q[3]) {
  TriTriResult result;
  // Triangles whose bounding boxes are apart cannot meet. The test is exact, so it rejects no
  // true contact, only uncertain-zone answers for pairs that are provably apart; and it makes
  // the answer consistent with broad phases that cull by exact bounding boxes (octree leaf
  // boxes are min/max of the same floats): any pair reported here has touching leaf boxes, so
  // every such broad phase returns exactly the pairs that testing all pairs returns.
  if (!boxes_touch(p, q)) return result;
  // Symmetry: process the pair in a canonical order (lexicographic on the 9 coordinates), so
  // that f(p, q) and f(q, p) run the same float operations and return the same result.
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
  glm::vec3 a[3];
  glm::vec3 b[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = swap ? q[i] : p[i];
    b[i] = swap ? p[i] : q[i];
  }

  // Degenerate triangles have no plane: no intersection (this also covers zero-length edges,
  // where both sides are 0, so nothing below divides by zero).
  const float la2 = longest_edge2(a);
  const float lb2 = longest_edge2(b);
  const glm::vec3 na = glm::cross(a[1] - a[0], a[2] - a[0]);
  const glm::vec3 nb = glm::cross(b[1] - b[0], b[2] - b[0]);
  const float na_len = glm::length(na);
  const float nb_len = glm::length(nb);
  if (!(na_len > kTriTriDegenerateTolerance * la2) || !(nb_len > kTriTriDegenerateTolerance * lb2))
    return result;
  const float size = std::sqrt(std::max(la2, lb2));
  const glm::vec3 ua = na / na_len;
  const glm::vec3 ub = nb / nb_len;

  // Signed distances of each triangle's vertices to the other's plane, snapped to the plane
  // within the tolerance above (divided by |n|, since the normals here are unit).
  const float tol_a = (kTriTriTolerance + kTriTriRoundoff * la2 / na_len) * size;
  const float tol_b = (kTriTriTolerance + kTriTriRoundoff * lb2 / nb_len) * size;
  float db[3];
  float da[3];
  for (int i = 0; i < 3; ++i) {
    db[i] = snap_to_zero(glm::dot(ua, b[i] - a[0]), tol_a);
    da[i] = snap_to_zero(glm::dot(ub, a[i] - b[0]), tol_b);
  }
  const bool b_on_plane_a = db[0] == 0.0f && db[1] == 0.0f && db[2] == 0.0f;
  const bool a_on_plane_b = da[0] == 0.0f && da[1] == 0.0f && da[2] == 0.0f;
  if (b_on_plane_a || a_on_plane_b) {
    result.coplanar = true;
    result.intersect = coplanar_overlap(a, b, na, size);
    return result;
  }
  if (same_strict_side(db) || same_strict_side(da)) return result;

  // Both triangles cross the line of the planes' intersection: overlap of their intervals.
  const glm::vec3 dir = glm::cross(ua, ub);
  const LineInterval ia = line_interval(a, da, dir, a[0]);
  const LineInterval ib = line_interval(b, db, dir, a[0]);
  const bool lo_from_a = ia.t_min >= ib.t_min;
  const bool hi_from_a = ia.t_max <= ib.t_max;
  const float t_lo = lo_from_a ? ia.t_min : ib.t_min;
  const float t_hi = hi_from_a ? ia.t_max : ib.t_max;
  const glm::vec3 x_lo = lo_from_a ? ia.x_min : ib.x_min;
  const glm::vec3 x_hi = hi_from_a ? ia.x_max : ib.x_max;
  if (t_lo > t_hi + kTriTriTolerance * size * glm::length(dir)) return result;
  // A vertex snapped onto the other plane was taken to lie on the planes' line, but it may lie
  // up to tolerance / sin(angle) from it: near parallel planes, that spans the triangles, and
  // two faces of a gently curved sheet 0.5 x their size apart were reported (found by the CGAL
  // oracle on the folding plate). Then each triangle's part on the other's plane (a segment
  // within tolerance of that plane) must meet the other triangle there, in 2D.
  const bool snapped = da[0] == 0.0f || da[1] == 0.0f || da[2] == 0.0f || db[0] == 0.0f ||
                       db[1] == 0.0f || db[2] == 0.0f;
  if (snapped && (!segment_in_plane_meets_triangle(ib.x_min, ib.x_max, a, na, size) ||
                  !segment_in_plane_meets_triangle(ia.x_min, ia.x_max, b, nb, size))) {
    return result;
  }
  result.intersect = true;
  const bool touching = t_lo > t_hi;  // a gap inside the tolerance: one contact point
  result.segment[0] = touching ? 0.5f * (x_lo + x_hi) : x_lo;
  result.segment[1] = touching ? 0.5f * (x_lo + x_hi) : x_hi;
  return result;
}

}  // namespace deformcd::collision
