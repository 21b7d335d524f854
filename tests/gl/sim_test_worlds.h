#pragma once
// Helpers for the GL simulation tests: deterministic noise, substep constants, stepping a
// backend, comparing states. The worlds themselves come from tests/support/world_fixtures.h.

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
#include "deformcd/simulation_state.h"
#include "support/world_fixtures.h"

namespace deformcd::test {

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
