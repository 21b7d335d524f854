#include "spring_topology.h"

#include <algorithm>
#include <unordered_set>

namespace deformcd {

std::vector<Edge> tetrahedron_edges(const std::vector<Tetrahedron>& tets, bool merge_shared) {
  constexpr int kLocalEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::vector<Edge> edges;
  edges.reserve(tets.size() * 6);
  std::unordered_set<std::uint64_t> seen;
  for (const Tetrahedron& t : tets) {
    for (const auto& e : kLocalEdges) {
      Edge edge{t[e[0]], t[e[1]]};
      if (merge_shared) {
        if (edge[0] > edge[1]) std::swap(edge[0], edge[1]);
        const std::uint64_t key = (std::uint64_t{edge[0]} << 32) | edge[1];
        if (!seen.insert(key).second) continue;
      }
      edges.push_back(edge);
    }
  }
  return edges;
}

}  // namespace deformcd
