#pragma once
// tri_tri_intersect_touching in two steps, for a caller that runs the first over a batch of
// candidate pairs before the second: the first answers "apart" for most of a broad phase's
// candidates (42 % of the bvh's on bench_peers' contact frames, at b's vertices against a's
// plane), and as a branch taken or not in each test that answer was mispredicted about as often
// as not (a third of the test's own time). Written without branches on the geometry, so that a
// loop over many pairs runs straight through and keeps the survivors.

#include "core/collision/tri_tri_intersection.h"
#include "core/collision/tri_tri_primitives.h"

namespace deformcd::collision {

/// A pair after the first step: in canonical order (a first), the pair's size and b's snapped
/// distances to a's plane.
struct TriTriPlaneStep {
  const TriangleGeometry* a;
  const TriangleGeometry* b;
  float size;
  float db[3];
};

/// The first step of tri_tri_intersect_touching(p, q), the same float operations: false when
/// it answers that they do not intersect (a triangle degenerate, or b wholly beyond a's plane),
/// else `step` holds what tri_tri_finish needs.
[[nodiscard]] inline bool tri_tri_plane_step(const TriangleGeometry& p, const TriangleGeometry& q,
                                             TriTriPlaneStep& step) {
  // The canonical order of tri_tri_intersect: the first coordinate that differs decides.
  bool swap = false;
  bool decided = false;
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) {
      const bool differ = p.v[k][c] != q.v[k][c];
      swap = swap | (!decided & differ & (q.v[k][c] < p.v[k][c]));
      decided = decided | differ;
    }
  }
  const TriangleGeometry& a = swap ? q : p;
  const TriangleGeometry& b = swap ? p : q;
  step.a = &a;
  step.b = &b;
  step.size = std::max(a.edge, b.edge);
  const float tol_a = a.rel_tol * step.size;
  for (int i = 0; i < 3; ++i)
    step.db[i] = detail::snap_to_zero(glm::dot(a.u, b.v[i] - a.v[0]), tol_a);
  const bool above = (step.db[0] > 0.0f) & (step.db[1] > 0.0f) & (step.db[2] > 0.0f);
  const bool below = (step.db[0] < 0.0f) & (step.db[1] < 0.0f) & (step.db[2] < 0.0f);
  return a.proper & !(above | below) & b.proper;
}

/// The rest of tri_tri_intersect_touching after a first step that returned true.
[[nodiscard]] TriTriResult tri_tri_finish(const TriTriPlaneStep& step);

}  // namespace deformcd::collision
