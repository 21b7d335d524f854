#include "stability_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

namespace deformcd::sim {

double estimate_max_stable_substep(const SimulationState& w) {
  // Row sums of |M^-1/2 K M^-1/2| by 3x3 blocks; fixed nodes (inverse mass 0) do not move.
  std::vector<double> row(w.node_count(), 0.0);
  auto inverse_mass = [&](std::uint32_t n) { return static_cast<double>(w.positions[n].w); };
  auto couple = [&](std::uint32_t i, std::uint32_t j, double block) {
    row[i] += block * std::sqrt(inverse_mass(i) * inverse_mass(j));
  };
  for (const gpu::Spring& s : w.springs) {
    const double k = s.stiffness;
    couple(s.a, s.a, k);
    couple(s.a, s.b, k);
    couple(s.b, s.b, k);
    couple(s.b, s.a, k);
  }
  for (const gpu::Tetra& t : w.tets) {
    if (t.stiffness == 0.0f) continue;
    const std::uint32_t n[4] = {t.a, t.b, t.c, t.d};
    const glm::dvec3 a(w.positions[t.a]), b(w.positions[t.b]), c(w.positions[t.c]),
        d(w.positions[t.d]);
    glm::dvec3 grad[4];
    grad[1] = glm::cross(c - a, d - a) / 6.0;
    grad[2] = glm::cross(d - a, b - a) / 6.0;
    grad[3] = glm::cross(b - a, c - a) / 6.0;
    grad[0] = -(grad[1] + grad[2] + grad[3]);
    // Hessian block (i, j) of c (V - V0)^2 / 2 at rest: c grad_i grad_j^T, norm c |g_i| |g_j|.
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        couple(n[i], n[j], t.stiffness * glm::length(grad[i]) * glm::length(grad[j]));
      }
    }
  }
  const double omega2 = row.empty() ? 0.0 : *std::max_element(row.begin(), row.end());
  if (!(omega2 > 0.0)) return std::numeric_limits<double>::infinity();
  return 2.0 / std::sqrt(omega2);
}

}  // namespace deformcd::sim
