#pragma once
// A layout of a SimulationState's force work that computes less and reads memory in order, and
// still gives every node the same force, bit for bit, as the per-spring passes the state
// describes (spring forces gathered over node_spring_list, tetrahedron corner forces gathered
// over node_tet_list).
//
// Springs -> edges. The paper's bodies have one spring per tetrahedron edge, so an edge shared by
// n tetrahedra carries n springs with the same two nodes and rest length (the lion: 108,870
// springs on 24,883 edges). A spring's force is (k q) u, with u the unit vector along it and
// q = (length - rest) + damping (dv . u) (sim::spring_force); u and q depend only on the two
// nodes, the rest length and the damping, and swapping the ends negates u exactly and keeps q
// exactly (negation is exact, and the dot products see the same products). So u and q are
// computed once per edge (the edge pass) and each node sums (k' q) u over its springs in its own
// list order, k' = +k when the node is the edge's first node and -k otherwise: the same
// floating-point operations on the same operands as +-(k q) u, in the same order.
//
// Tetrahedra -> node-major corner slots. Each tetrahedron with nonzero stiffness writes its four
// corner forces where its corners' nodes read them, so that a node reads its corners
// contiguously instead of scattered over 4 x tetrahedra slots. Tetrahedra with zero stiffness
// are left out: their corner forces are +0, and adding +0 to a sum that starts at +0 never
// changes it (in round-to-nearest such a sum is never -0).

#include <cstdint>
#include <vector>

#include "deformcd/gpu_layout.h"
#include "deformcd/simulation_state.h"

namespace deformcd::sim {

/// One entry of a node's spring list: the edge, and the spring's stiffness signed for this node
/// (+k if the node is the edge's node a, -k if its node b); the GL step reads the same array.
using EdgeTerm = gpu::EdgeTerm;

/// Every distinct (node a, node b, rest length, damping) of a state's springs once, with a < b,
/// sorted by (a, b); and per node its springs in the order of the state's node_spring_list.
struct SpringEdges {
  std::vector<std::uint32_t> a;            ///< first node, the smaller index
  std::vector<std::uint32_t> b;            ///< second node
  std::vector<float> rest_length;          ///< m
  std::vector<float> damping;              ///< s, of the body of the springs' end a
  std::vector<std::uint32_t> node_offset;  ///< nodes + 1 entries, into node_terms
  std::vector<EdgeTerm> node_terms;        ///< per node, in node_spring_list order

  [[nodiscard]] std::size_t size() const { return a.size(); }
};

/// The tetrahedra with nonzero stiffness, each with the four slots its corner forces go to; the
/// slots of node i are [node_offset[i], node_offset[i + 1]), in node_tet_list order.
struct TetCorners {
  std::vector<gpu::Tetra> tets;            ///< the stiff tetrahedra, in state order
  std::vector<std::uint32_t> corner_slot;  ///< 4 per tetrahedron: corners a, b, c, d
  std::vector<std::uint32_t> node_offset;  ///< nodes + 1 entries, into the slots
  /// Slots to allocate: node_offset.back(), plus one that no node reads for the corners of a
  /// stiff tetrahedron that no node lists.
  std::uint32_t slot_count = 0;
};

/// Builds both from a consistent state (as assemble_simulation makes: every list entry names an
/// existing spring or corner slot, each corner slot listed at most once). Throws Error otherwise.
[[nodiscard]] SpringEdges build_spring_edges(const SimulationState& state);
[[nodiscard]] TetCorners build_tet_corners(const SimulationState& state);

}  // namespace deformcd::sim
