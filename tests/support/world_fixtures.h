#pragma once
// Worlds built in code for simulation tests.

#include <cstdint>
#include <vector>

#include "deformcd/body.h"
#include "deformcd/world_state.h"
#include "support/mesh_fixtures.h"

namespace deformcd::test {

/// A grid of nx x ny x nz unit cubes (spacing `h`), each split into 5 tetrahedra with
/// alternating orientation so that neighbouring cubes share their face diagonals.
inline TetMesh cube_grid(int nx, int ny, int nz, double h = 0.1) {
  TetMesh m;
  auto id = [&](int i, int j, int k) {
    return static_cast<std::uint32_t>((k * (ny + 1) + j) * (nx + 1) + i);
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.nodes.push_back({i * h, j * h, k * h});
  const TetMesh unit = unit_cube();
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool flip = (i + j + k) % 2 == 1;  // mirror in x so diagonals match neighbours
        for (const Tetrahedron& t : unit.tetrahedra) {
          Tetrahedron g{};
          for (int c = 0; c < 4; ++c) {
            const glm::dvec3 p = unit.nodes[t[c]];
            const int px = flip ? 1 - static_cast<int>(p.x) : static_cast<int>(p.x);
            g[c] = id(i + px, j + static_cast<int>(p.y), k + static_cast<int>(p.z));
          }
          if (flip) std::swap(g[2], g[3]);  // mirroring flips orientation; restore it
          m.tetrahedra.push_back(g);
        }
      }
  return m;
}

/// Two nodes joined by one spring, on the x axis: masses m1, m2 at distance `length`, rest
/// length `rest`, stiffness k (N/m). No faces: fine for a backend, not for a World.
inline WorldState two_mass_spring(float m1, float m2, float rest, float length, float k) {
  WorldState w;
  w.positions = {{0, 0, 0, 1.0f / m1}, {length, 0, 0, 1.0f / m2}};
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

}  // namespace deformcd::test
