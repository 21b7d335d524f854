#pragma once
/// \file simulation_state.h
/// The mass-spring state of every body of a world, concatenated into the arrays the GPU buffers
/// hold (one array per buffer, see gpu_layout.h). Both simulation backends start from it; the
/// CPU backend steps it in place, the GL backend uploads it. Collision detection keeps its own
/// data (a Detector over the bodies' surfaces) and only reads the positions.

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/body.h"
#include "deformcd/gpu_layout.h"

namespace deformcd {

/// One body as it enters a world: its arrays plus what the world needs to know about it.
struct BodyInit {
  Body body;             ///< positions already transformed into the scene
  float damping = 0.0f;  ///< s: each spring's damping = damping x its stiffness
  /// Pa: resistance of each tetrahedron to volume change, force from the energy
  /// k (V - V0)^2 / (2 L^3), L the tetrahedron's mean rest edge length (after Teschner et al.
  /// 2004, who divide by 2 V0; L^3 keeps slivers from becoming arbitrarily stiff); 0 keeps the
  /// paper's springs-only model.
  float volume_stiffness = 0.0f;
  glm::vec3 carry_velocity{0.0f};    ///< m/s, the body's path
  std::vector<std::uint32_t> fixed;  ///< local indices of nodes held in place
  std::string name;                  ///< for messages and outputs
};

/// Global step settings shared by all bodies.
struct StepSettings {
  float dt = 1.0f / 60.0f;                ///< seconds per frame
  int substeps = 1;                       ///< integration steps per frame (step = dt / substeps)
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};  ///< m/s^2
  float velocity_damping = 0.0f;          ///< 1/s
};

/// Every body's data, concatenated; indices are global. The per-spring and per-corner arrays are
/// the paper's layout (its Table 1, SSBOs 2 and 14-20); both backends derive from them the
/// layout they step with (src/core/sim/node_force_lists.h: each spring edge once, corners node
/// by node), and the GL backend uploads that one at those binding points (gpu::Binding).
struct SimulationState {
  std::vector<glm::vec4> positions;               ///< SSBO 0: xyz, w = inverse mass (0 = fixed)
  std::vector<glm::vec4> velocities;              ///< SSBO 1: xyz, w = 0
  std::vector<gpu::Spring> springs;               ///< the paper's SSBO 2
  std::vector<glm::vec4> forces;                  ///< SSBO 3: summed spring forces per node
  std::vector<gpu::ObjectInfo> objects;           ///< SSBO 8
  std::vector<gpu::BodyParams> body_params;       ///< SSBO 12
  std::vector<std::uint32_t> node_body;           ///< SSBO 13
  std::vector<glm::vec4> spring_forces;           ///< the paper's SSBO 14 (no backend writes it)
  std::vector<std::uint32_t> node_spring_offset;  ///< nodes + 1 entries
  std::vector<gpu::Tetra> tets;                   ///< every tetrahedron
  std::vector<glm::vec4> tet_forces;              ///< 4 per tetrahedron (no backend writes it)
  std::vector<std::uint32_t> node_tet_offset;     ///< nodes + 1 entries
  std::vector<std::uint32_t> node_tet_list;       ///< 4 x tetrahedra entries: slots 4 t + k
  std::vector<std::int32_t> node_spring_list;     ///< 2 x springs: +(s+1) at end a, -(s+1) at b
  std::vector<std::string> body_names;            ///< one per body, in body order

  [[nodiscard]] std::size_t node_count() const {
    return positions.size();
  }                                                                        ///< nodes of every body
  [[nodiscard]] std::size_t body_count() const { return objects.size(); }  ///< bodies
};

/// Concatenates bodies into one world state: offsets indices, sets inverse masses (0 for fixed
/// nodes), builds the per-node spring lists (CSR, springs in increasing index order, so that
/// the force sum has one fixed order on every backend). Throws InputError for a fixed node index
/// out of range or a body without surface faces.
[[nodiscard]] SimulationState assemble_simulation(const std::vector<BodyInit>& bodies);

}  // namespace deformcd
