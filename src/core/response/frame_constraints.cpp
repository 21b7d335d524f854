#include "core/response/frame_constraints.h"

namespace deformcd::response {

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
