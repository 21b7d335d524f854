#pragma once
// The body-level broad phase (beyond the paper): which pairs of different bodies have touching
// bounding boxes, by sort and sweep along x, so that a scene of many bodies tests only the
// pairs that are near each other instead of all B (B - 1) / 2.

#include <vector>

#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Pairs (a < b) of bodies whose closed boxes overlap, sorted by (a, b). O(B log B + pairs
/// overlapping along x). An empty box (no faces) overlaps nothing.
[[nodiscard]] std::vector<gpu::BodyPair> overlapping_body_pairs(const std::vector<gpu::Box>& boxes);

}  // namespace deformcd::collision
