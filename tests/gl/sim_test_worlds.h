#pragma once
// Small worlds for the simulation tests, built in code: a tetrahedral grid (there is no
// tetrahedralizer in the GL tests), worlds assembled from it, and helpers to step a backend.

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/sim/mass_spring.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/body.h"
#include "deformcd/mesh.h"
#include "deformcd/world_state.h"

namespace deformcd::test {

/// A box of nx x ny x nz cubes of side `spacing` from `origin`, each cube split into the 6
/// tetrahedra of its Kuhn (Freudenthal) triangulation along the (1,1,1) diagonal, which is
/// conforming across cubes. Node (i, j, k) has index i + (nx+1) (j + (ny+1) k).
inline TetMesh tet_grid(int nx, int ny, int nz, double spacing, glm::dvec3 origin = {}) {
  TetMesh m;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.nodes.push_back(origin + spacing * glm::dvec3(i, j, k));
  auto index = [&](int i, int j, int k) {
    return static_cast<std::uint32_t>(i + (nx + 1) * (j + (ny + 1) * k));
  };
  constexpr std::array<std::array<int, 3>, 6> kAxisOrders = {
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const std::array<int, 3>& order : kAxisOrders) {
          // A monotone path from corner (0,0,0) to (1,1,1), one axis at a time.
          std::array<int, 3> c = {i, j, k};
          Tetrahedron t{};
          t[0] = index(c[0], c[1], c[2]);
          for (int step = 0; step < 3; ++step) {
            ++c[order[step]];
            t[step + 1] = index(c[0], c[1], c[2]);
          }
          const glm::dvec3 a = m.nodes[t[0]];
          if (glm::dot(m.nodes[t[1]] - a, glm::cross(m.nodes[t[2]] - a, m.nodes[t[3]] - a)) < 0) {
            std::swap(t[2], t[3]);
          }
          m.tetrahedra.push_back(t);
        }
  return m;
}

/// Deterministic pseudo-random value in [-1, 1] for (i, salt): the same on every platform,
/// unlike std:: distributions.
inline float hash_unit(std::uint32_t i, std::uint32_t salt) {
  std::uint32_t x = i * 747796405u + salt * 2891336453u + 1u;
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return static_cast<float>(x) / 2147483647.5f - 1.0f;
}

/// Constants for a substep of length h with the given gravity and velocity damping.
inline sim::SubstepConstants substep_constants(float h, glm::vec3 gravity = glm::vec3(0.0f),
                                               float velocity_damping = 0.0f) {
  return {h, gravity, std::exp(-velocity_damping * h)};
}

/// Runs `count` substeps.
inline void run_substeps(sim::SimulationBackend& backend, const sim::SubstepConstants& c,
                         int count) {
  for (int i = 0; i < count; ++i)
    backend.substep(c);
}

/// Largest distance between corresponding xyz of two equally long arrays.
inline float max_distance(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    worst = std::max(worst, glm::distance(glm::vec3(a[i]), glm::vec3(b[i])));
  }
  return worst;
}

/// Largest xyz length in an array.
inline float max_length(const std::vector<glm::vec4>& a) {
  float worst = 0.0f;
  for (const glm::vec4& v : a)
    worst = std::max(worst, glm::length(glm::vec3(v)));
  return worst;
}

}  // namespace deformcd::test
