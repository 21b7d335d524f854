#pragma once
// Bodies a substep may skip. A body none of whose nodes can move (every inverse mass 0: a fixed
// base, or a body the contact response put to sleep) and that no path carries (carry velocity
// 0) stays where it is through any number of substeps: integrate_node gives a fixed node
// velocity 0 and moves it by its carry velocity alone. Once a substep has stepped it with its
// velocities at 0 (the one after its velocities were zeroed: by set_inverse_masses, or by its
// first substep), its node forces are those of its resting positions, and further substeps
// would compute the same values again, so both backends skip its springs, tetrahedra and
// nodes: the results are bit for bit those of stepping it. A body frozen so thaws as soon as
// one of its nodes gets an inverse mass above 0 again.

#include <cstdint>
#include <span>
#include <vector>

#include "deformcd/simulation_state.h"

namespace deformcd::sim {

class FrozenBodies {
 public:
  FrozenBodies() = default;
  /// Over `state`'s nodes and bodies (inverse masses in positions[i].w): no body frozen yet;
  /// each body that cannot move freezes after two substeps (its velocities may not be 0).
  explicit FrozenBodies(const SimulationState& state);

  /// Nodes [first, first + inverse_mass.size()) got those inverse masses and velocity 0 (a
  /// range the backend has checked): a body that cannot move now freezes after the next
  /// substep. Returns whether a frozen body thawed (it must be stepped from now on).
  bool set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass);
  /// After a substep: the bodies that could not move during it are frozen from now on.
  /// Returns whether any body froze.
  bool after_substep();

  /// Per body: 1 when substeps skip it, else 0.
  [[nodiscard]] const std::vector<std::uint8_t>& frozen() const { return frozen_; }
  [[nodiscard]] bool frozen(std::uint32_t body) const { return frozen_[body] != 0u; }
  /// Whether body b can move now: a node of it has an inverse mass above 0, or a path carries
  /// it. The one definition the substeps (which skip the others once frozen), sleeping (which
  /// holds a body still by its nodes' inverse masses) and the contact response (whose
  /// constraints between two bodies that cannot move would correct nothing) share.
  [[nodiscard]] bool can_move(std::uint32_t body) const { return still_[body] == 0u; }

 private:
  /// can_move(b) measured on the inverse masses now.
  [[nodiscard]] bool movable(std::uint32_t body) const;

  std::vector<float> inverse_mass_;                     // per node
  std::vector<std::uint32_t> node_body_;                // per node
  std::vector<std::uint32_t> first_node_, node_count_;  // per body: its nodes (contiguous)
  std::vector<std::uint8_t> carried_;                   // per body: a nonzero carry velocity
  // Per body: 0 when it can move, else the substeps still to step before it freezes (0 once
  // frozen).
  std::vector<std::uint8_t> still_;
  std::vector<std::uint8_t> until_frozen_;
  std::vector<std::uint8_t> frozen_;  // per body: skipped by substeps
};

/// Per element of a batch of `batch` consecutive elements (each the nodes `nodes_of(e, out)`
/// fills, at most 4): whether every node of every element of batch k lies in a frozen body,
/// so that the whole batch may be skipped.
template <class NodesOf>
std::vector<std::uint8_t> frozen_batches(std::size_t count, std::size_t batch,
                                         const std::vector<std::uint32_t>& node_body,
                                         const std::vector<std::uint8_t>& frozen,
                                         const NodesOf& nodes_of) {
  std::vector<std::uint8_t> out((count + batch - 1) / batch, 1u);
  for (std::size_t e = 0; e < count; ++e) {
    std::uint32_t nodes[4];
    const std::uint32_t n = nodes_of(e, nodes);
    for (std::uint32_t k = 0; k < n; ++k)
      if (frozen[node_body[nodes[k]]] == 0u) out[e / batch] = 0u;
  }
  return out;
}

}  // namespace deformcd::sim
