#pragma once
// Springs of a tetrahedral mass-spring body: one per tetrahedron edge (the paper), or one per
// distinct edge.

#include <array>
#include <cstdint>
#include <vector>

#include "deformcd/mesh.h"

namespace deformcd {

/// An edge and the tetrahedra it stands for (one, or all that share it when merged).
struct TetEdge {
  std::array<std::uint32_t, 2> nodes;
  std::vector<std::uint32_t> tetrahedra;
};

/// The six edges of every tetrahedron in order (ab, ac, ad, bc, bd, cd), 6 x tets.size() edges.
/// With `merge_shared`, each distinct edge once, in order of first appearance, smaller index
/// first, with every tetrahedron that shares it.
[[nodiscard]] std::vector<TetEdge> tetrahedron_edges(const std::vector<Tetrahedron>& tets,
                                                     bool merge_shared);

}  // namespace deformcd
