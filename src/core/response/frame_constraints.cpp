#include "frame_constraints.h"

namespace deformcd::response {

void index_constraints_by_node(std::uint32_t node_count, FrameConstraints& c) {
  c.node_offset.assign(std::size_t{node_count} + 1u, 0u);
  for (const gpu::ContactPair& p : c.pairs)
    for (std::uint32_t k = 0; k < 4u; ++k)
      ++c.node_offset[p.nodes[k] + 1u];
  for (std::uint32_t n = 0; n < node_count; ++n)
    c.node_offset[n + 1u] += c.node_offset[n];
  c.node_list.assign(c.node_offset[node_count], 0u);
  std::vector<std::uint32_t> next(c.node_offset.begin(), c.node_offset.end() - 1);
  for (std::uint32_t p = 0; p < c.pairs.size(); ++p)
    for (std::uint32_t k = 0; k < 4u; ++k)
      c.node_list[next[c.pairs[p].nodes[k]]++] = 4u * p + k;
}

}  // namespace deformcd::response
