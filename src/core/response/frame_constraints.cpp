#include "core/response/frame_constraints.h"

#include <string>

#include "deformcd/error.h"

namespace deformcd::response {

std::size_t first_volume_constraint(const std::vector<gpu::ContactPair>& pairs) {
  std::size_t first = pairs.size();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (pairs[p].kind == gpu::kContactVolume) {
      if (first == pairs.size()) first = p;
    } else if (first < p) {
      throw Error("FrameConstraints: constraint " + std::to_string(p) + " (kind " +
                  std::to_string(pairs[p].kind) + ") follows volume constraint " +
                  std::to_string(first) + "; the volume constraints must come last");
    }
  }
  return first;
}

NodeContactLists index_constraints_by_node(std::uint32_t node_count,
                                           const std::vector<gpu::ContactPair>& pairs) {
  NodeContactLists c;
  c.offset.assign(std::size_t{node_count} + 1u, 0u);
  for (const gpu::ContactPair& p : pairs)
    for (std::uint32_t k = 0; k < 4u; ++k)
      ++c.offset[p.nodes[k] + 1u];
  for (std::uint32_t n = 0; n < node_count; ++n)
    c.offset[n + 1u] += c.offset[n];
  c.list.assign(c.offset[node_count], 0u);
  std::vector<std::uint32_t> next(c.offset.begin(), c.offset.end() - 1);
  for (std::uint32_t p = 0; p < pairs.size(); ++p)
    for (std::uint32_t k = 0; k < 4u; ++k)
      c.list[next[pairs[p].nodes[k]]++] = 4u * p + k;
  return c;
}

}  // namespace deformcd::response
