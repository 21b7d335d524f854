#include "cpu_simulation.h"

#include "core/sim/mass_spring.h"
#include "parallel_for.h"

namespace deformcd::cpu {

CpuSimulation::CpuSimulation(std::shared_ptr<Executor> executor) : executor_(std::move(executor)) {}

std::string CpuSimulation::device() const {
  return executor_->describe();
}

void CpuSimulation::upload(const SimulationState& state) {
  state_ = state;
}

void CpuSimulation::substep(const sim::SubstepConstants& c) {
  executor_->run([&] { step(c); });
}

void CpuSimulation::step(const sim::SubstepConstants& c) {
  SimulationState& w = state_;
  // SpringUpdate: one spring per element.
  parallel_for(w.springs.size(), [&](std::size_t s) {
    const gpu::Spring& spring = w.springs[s];
    const gpu::BodyParams& p = w.body_params[w.node_body[spring.a]];
    w.spring_forces[s] = glm::vec4(
        sim::spring_force(glm::vec3(w.positions[spring.a]), glm::vec3(w.positions[spring.b]),
                          glm::vec3(w.velocities[spring.a]), glm::vec3(w.velocities[spring.b]),
                          spring.rest_length, spring.stiffness, p.damping),
        0.0f);
  });
  // TetUpdate: one tetrahedron per element, its four corner forces.
  parallel_for(w.tets.size(), [&](std::size_t t) {
    const gpu::Tetra& tet = w.tets[t];
    if (tet.stiffness == 0.0f) return;  // stays zero from assembly
    glm::vec3 f[4];
    sim::tet_volume_forces(glm::vec3(w.positions[tet.a]), glm::vec3(w.positions[tet.b]),
                           glm::vec3(w.positions[tet.c]), glm::vec3(w.positions[tet.d]),
                           tet.rest_volume, tet.stiffness, f);
    for (int k = 0; k < 4; ++k)
      w.tet_forces[4 * t + k] = glm::vec4(f[k], 0.0f);
  });
  // NodeForce: gather each node's springs, then its tetrahedron corners; NodeUpdate: integrate it.
  // Both per node, fused on the CPU since nothing reads another node's force.
  parallel_for(w.positions.size(), [&](std::size_t i) {
    const glm::vec3 f =
        sim::gather_node_force(w.node_spring_list.data(), w.node_spring_offset[i],
                               w.node_spring_offset[i + 1], w.spring_forces.data()) +
        sim::gather_tet_force(w.node_tet_list.data(), w.node_tet_offset[i],
                              w.node_tet_offset[i + 1], w.tet_forces.data());
    w.forces[i] = glm::vec4(f, 0.0f);
    sim::integrate_node(w.positions[i], w.velocities[i], f,
                        glm::vec3(w.body_params[w.node_body[i]].carry_velocity), c);
  });
}

}  // namespace deformcd::cpu
