#include "core/sim/stability_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

namespace deformcd::sim {

double estimate_max_stable_substep(const SimulationState& w) {
  // Row sums of |M^-1/2 K M^-1/2| (stiffness) and of |M^-1/2 C M^-1/2| (damping) by 3x3 blocks;
  // fixed nodes (inverse mass 0) do not move.
  std::vector<double> stiffness_row(w.node_count(), 0.0);
  std::vector<double> damping_row(w.node_count(), 0.0);
  auto weight = [&](std::uint32_t i, std::uint32_t j) {
    return std::sqrt(static_cast<double>(w.positions[i].w) * static_cast<double>(w.positions[j].w));
  };
  for (const gpu::Spring& s : w.springs) {
    const double k = s.stiffness;
    // A spring's damping force is damping x k x the relative velocity along it (mass_spring.h).
    const double c = static_cast<double>(w.body_params[w.node_body[s.a]].damping) * k;
    for (const std::uint32_t i : {s.a, s.b}) {
      for (const std::uint32_t j : {s.a, s.b}) {
        stiffness_row[i] += k * weight(i, j);
        damping_row[i] += c * weight(i, j);
      }
    }
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
        stiffness_row[n[i]] +=
            t.stiffness * glm::length(grad[i]) * glm::length(grad[j]) * weight(n[i], n[j]);
      }
    }
  }
  // Row i certifies h^2 k_i + 2 h c_i <= 4 up to its root h_i = 4 / (c_i + sqrt(c_i^2 + 4 k_i))
  // (the quadratic's positive root, written without the cancellation of -c + sqrt(...)).
  double h = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < stiffness_row.size(); ++i) {
    const double k = stiffness_row[i], c = damping_row[i];
    if (!(k > 0.0) && !(c > 0.0)) continue;
    h = std::min(h, 4.0 / (c + std::sqrt(c * c + 4.0 * k)));
  }
  return h;
}

}  // namespace deformcd::sim
