#include "core/spring_topology.h"

#include <algorithm>
#include <unordered_map>

namespace deformcd {

std::vector<TetEdge> tetrahedron_edges(const std::vector<Tetrahedron>& tets, bool merge_shared) {
  constexpr int kLocalEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  std::vector<TetEdge> edges;
  edges.reserve(merge_shared ? tets.size() * 2 : tets.size() * 6);
  std::unordered_map<std::uint64_t, std::size_t> index_of;  // merged: edge key -> position
  for (std::uint32_t t = 0; t < tets.size(); ++t) {
    for (const auto& e : kLocalEdges) {
      std::array<std::uint32_t, 2> nodes{tets[t][e[0]], tets[t][e[1]]};
      if (!merge_shared) {
        edges.push_back({nodes, {t}});
        continue;
      }
      if (nodes[0] > nodes[1]) std::swap(nodes[0], nodes[1]);
      const std::uint64_t key = (std::uint64_t{nodes[0]} << 32) | nodes[1];
      auto [it, inserted] = index_of.emplace(key, edges.size());
      if (inserted) {
        edges.push_back({nodes, {t}});
      } else {
        edges[it->second].tetrahedra.push_back(t);
      }
    }
  }
  return edges;
}

}  // namespace deformcd
