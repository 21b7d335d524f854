#include "core/collision/body_pairs.h"

#include <algorithm>
#include <numeric>

#include "core/collision/broad_phase.h"

namespace deformcd::collision {

std::vector<gpu::BodyPair> overlapping_body_pairs(const std::vector<gpu::Box>& boxes) {
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return boxes[x].min.x < boxes[y].min.x || (boxes[x].min.x == boxes[y].min.x && x < y);
  });
  std::vector<gpu::BodyPair> pairs;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const gpu::Box& bi = boxes[order[i]];
    // The sweep: every later box starting at or before bi's end overlaps it along x.
    for (std::size_t j = i + 1; j < order.size() && boxes[order[j]].min.x <= bi.max.x; ++j) {
      if (!boxes_overlap(bi, boxes[order[j]])) continue;
      pairs.push_back({std::min(order[i], order[j]), std::max(order[i], order[j])});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const gpu::BodyPair& x, const gpu::BodyPair& y) {
    return x.a < y.a || (x.a == y.a && x.b < y.b);
  });
  return pairs;
}

}  // namespace deformcd::collision
