#include "world/simulation_factory.h"

#include "cpu/cpu_contact_response.h"
#include "cpu/cpu_simulation.h"
#include "detector/backend_choice.h"

namespace deformcd {

std::unique_ptr<sim::SimulationBackend> create_simulation(BackendKind kind, gl::Context* context,
                                                          std::shared_ptr<cpu::Executor> executor) {
  if (kind == BackendKind::kGl) return make_gl_simulation(*context);
  return std::make_unique<cpu::CpuSimulation>(std::move(executor));
}

std::unique_ptr<response::ResponseBackend> create_response(
    BackendKind kind, gl::Context* context, sim::SimulationBackend& simulation,
    std::shared_ptr<cpu::Executor> executor) {
  if (kind == BackendKind::kGl) return make_gl_response(*context, simulation);
  return std::make_unique<cpu::CpuContactResponse>(simulation, std::move(executor));
}

}  // namespace deformcd
