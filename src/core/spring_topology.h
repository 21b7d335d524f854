#pragma once
// Springs of a tetrahedral mass-spring body: one per tetrahedron edge (the paper), or one per
// distinct edge.

#include <array>
#include <cstdint>
#include <vector>

#include "deformcd/mesh.h"

namespace deformcd {

using Edge = std::array<std::uint32_t, 2>;

/// The six edges of every tetrahedron in order (ab, ac, ad, bc, bd, cd), 6 x tets.size() edges.
/// With `merge_shared`, each distinct edge once, in order of first appearance, smaller index
/// first.
[[nodiscard]] std::vector<Edge> tetrahedron_edges(const std::vector<Tetrahedron>& tets,
                                                  bool merge_shared);

}  // namespace deformcd
