#include "core/sim/frozen_bodies.h"

#include <glm/vec3.hpp>

namespace deformcd::sim {

FrozenBodies::FrozenBodies(const SimulationState& state) : node_body_(state.node_body) {
  const std::size_t bodies = state.body_params.size();
  inverse_mass_.resize(state.positions.size());
  for (std::size_t i = 0; i < inverse_mass_.size(); ++i)
    inverse_mass_[i] = state.positions[i].w;
  carried_.resize(bodies);
  for (std::size_t b = 0; b < bodies; ++b)
    carried_[b] = glm::vec3(state.body_params[b].carry_velocity) != glm::vec3(0.0f) ? 1u : 0u;
  // A body's nodes are contiguous (assemble_simulation lays them out body after body); a state
  // that interleaves them gets a body's whole span, which can only make it move more often.
  first_node_.assign(bodies, 0u);
  node_count_.assign(bodies, 0u);
  std::vector<std::uint8_t> seen(bodies, 0u);
  for (std::uint32_t i = 0; i < node_body_.size(); ++i) {
    const std::uint32_t b = node_body_[i];
    if (seen[b] == 0u) {
      first_node_[b] = i;
      seen[b] = 1u;
    }
    node_count_[b] = i + 1u - first_node_[b];
  }
  still_.resize(bodies);
  until_frozen_.assign(bodies, 0u);
  for (std::uint32_t b = 0; b < bodies; ++b) {
    still_[b] = movable(b) ? 0u : 1u;
    if (still_[b] != 0u) until_frozen_[b] = 2u;  // the first substep zeroes its velocities
  }
  frozen_.assign(bodies, 0u);
}

bool FrozenBodies::movable(std::uint32_t body) const {
  if (carried_[body] != 0u) return true;
  for (std::uint32_t i = first_node_[body]; i < first_node_[body] + node_count_[body]; ++i)
    if (node_body_[i] == body && inverse_mass_[i] > 0.0f) return true;
  return false;
}

bool FrozenBodies::set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) {
  std::vector<std::uint32_t> touched;
  for (std::size_t k = 0; k < inverse_mass.size(); ++k) {
    inverse_mass_[first + k] = inverse_mass[k];
    const std::uint32_t b = node_body_[first + k];
    if (touched.empty() || touched.back() != b) touched.push_back(b);
  }
  bool thawed = false;
  for (const std::uint32_t b : touched) {
    still_[b] = movable(b) ? 0u : 1u;
    if (still_[b] == 0u) {
      thawed = thawed || frozen_[b] != 0u;
      frozen_[b] = 0u;
    } else if (frozen_[b] == 0u) {
      until_frozen_[b] = 1u;  // its velocities are 0 now
    }
  }
  return thawed;
}

bool FrozenBodies::after_substep() {
  bool froze = false;
  for (std::size_t b = 0; b < still_.size(); ++b) {
    if (still_[b] == 0u || frozen_[b] != 0u) continue;
    if (--until_frozen_[b] == 0u) {
      frozen_[b] = 1u;
      froze = true;
    }
  }
  return froze;
}

}  // namespace deformcd::sim
