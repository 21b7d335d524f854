#pragma once
// Worlds built in code for simulation tests.

#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "deformcd/body.h"
#include "deformcd/simulation_state.h"
#include "deformcd/world.h"
#include "support/mesh_fixtures.h"

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

/// Two nodes joined by one spring: masses m1 at `start` and m2 at `start + length x axis`
/// (axis a unit vector), rest length `rest`, stiffness k (N/m), undamped. No faces and no
/// tetrahedra: fine for a backend, not for a World.
inline SimulationState two_mass_spring(float m1, float m2, float rest, float length, float k,
                                       glm::vec3 start = glm::vec3(0.0f),
                                       glm::vec3 axis = glm::vec3(1.0f, 0.0f, 0.0f)) {
  SimulationState w;
  w.positions = {glm::vec4(start, 1.0f / m1), glm::vec4(start + length * axis, 1.0f / m2)};
  w.velocities = {glm::vec4(0.0f), glm::vec4(0.0f)};
  w.springs = {{0, 1, rest, k}};
  w.forces.assign(2, glm::vec4(0.0f));
  w.spring_forces.assign(1, glm::vec4(0.0f));
  w.objects = {gpu::ObjectInfo{0, 2, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0}};
  w.body_params = {{glm::vec4(0.0f), 0.0f, 0.0f, 0.0f, 0.0f}};
  w.node_body = {0, 0};
  w.node_spring_offset = {0, 1, 2};
  w.node_spring_list = {1, -1};
  w.node_tet_offset = {0, 0, 0};
  w.body_names = {"spring"};
  return w;
}

/// The sleeping tests' world (ResponseSettings::sleep): a fixed slab (body 0, 0.3 m square,
/// its top at y = 0) and two soft blocks of 0.1 m side over it: block 1 ("lower") 15 mm above
/// the slab, block 2 ("upper") `lift` m above block 1, both falling from rest.
inline std::vector<BodyInit> blocks_over_a_slab(double lift) {
  std::vector<BodyInit> bodies(3);
  bodies[0].name = "slab";
  bodies[0].body = build_body(tet_grid(6, 1, 6, 0.05, {-0.15, -0.05, -0.15}));
  for (std::uint32_t i = 0; i < bodies[0].body.positions.size(); ++i)
    bodies[0].fixed.push_back(i);
  BodyOptions soft;
  soft.stiffness = 1.0e5;
  for (int b = 1; b < 3; ++b) {
    const double bottom = b == 1 ? 0.015 : 0.115 + lift;
    bodies[b].name = b == 1 ? "lower" : "upper";
    bodies[b].body = build_body(tet_grid(2, 2, 2, 0.05, {-0.05, bottom, -0.05}), soft);
    bodies[b].damping = 0.0002f;
    bodies[b].volume_stiffness = 1.0e5f;
  }
  return bodies;
}

/// The sleeping tests' step: 60 frames a second, 10 substeps, velocity damping 4 / s.
inline StepSettings sleep_step() {
  StepSettings s;
  s.dt = 1.0f / 60.0f;
  s.substeps = 10;
  s.velocity_damping = 4.0f;
  return s;
}

/// Contact response with sleeping (every default), on `backend` with `threads` CPU threads.
inline WorldOptions sleep_options(BackendKind backend, int threads = 0) {
  WorldOptions options;
  options.backend = backend;
  options.cpu_threads = threads;
  options.response = ResponseSettings{};
  options.response->sleep = SleepSettings{};
  return options;
}

/// Three jittered grid bodies with random velocities, side by side, for the frozen-body tests
/// (core/sim/frozen_bodies.h): body 0 has every node fixed and no path (its velocities are
/// zeroed by its first substep), bodies 1 and 2 are free (the tests put body 2 to sleep).
inline SimulationState three_bodies_one_fixed() {
  std::vector<BodyInit> bodies(3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-0.02f, 0.02f), speed(-0.5f, 0.5f);
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    bodies[n].body = build_body(tet_grid(6, 5, 4, 0.1, {1.0 * static_cast<double>(n), 0.0, 0.0}),
                                {.stiffness = 5e4});
    for (auto& p : bodies[n].body.positions)
      p += glm::vec4(jitter(rng), jitter(rng), jitter(rng), 0.0f);
    for (auto& v : bodies[n].body.velocities)
      v = glm::vec4(speed(rng), speed(rng), speed(rng), 0.0f);
    bodies[n].damping = 1e-3f;
    bodies[n].volume_stiffness = 2e4f;
  }
  for (std::uint32_t i = 0; i < bodies[0].body.positions.size(); ++i)
    bodies[0].fixed.push_back(i);
  return assemble_simulation(bodies);
}

/// Body b's nodes' inverse masses in `state` (positions[i].w), in node order.
inline std::vector<float> inverse_masses(const SimulationState& state, std::uint32_t b) {
  const gpu::ObjectInfo& o = state.objects[b];
  std::vector<float> w(o.node_count);
  for (std::uint32_t k = 0; k < o.node_count; ++k)
    w[k] = state.positions[o.node_offset + k].w;
  return w;
}

}  // namespace deformcd::test
