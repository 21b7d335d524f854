#include "world/simulation_factory.h"

#include "cpu/cpu_contact_response.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/error.h"
#ifdef DEFORMCD_HAS_GL
#include "gpu/gl/gl_contact_response.h"
#include "gpu/gl/gl_simulation.h"
#endif

namespace deformcd {

std::unique_ptr<sim::SimulationBackend> create_simulation(BackendKind kind, gl::Context* context,
                                                          std::shared_ptr<cpu::Executor> executor) {
  if (kind == BackendKind::kGl) {
#ifdef DEFORMCD_HAS_GL
    return std::make_unique<gl::GlSimulation>(*context);
#else
    (void)context;
    throw GlError("this deformcd was built without the OpenGL backend (DEFORMCD_WITH_GL=OFF)");
#endif
  }
  return std::make_unique<cpu::CpuSimulation>(std::move(executor));
}

std::unique_ptr<response::ResponseBackend> create_response(
    BackendKind kind, gl::Context* context, sim::SimulationBackend& simulation,
    std::shared_ptr<cpu::Executor> executor) {
  if (kind == BackendKind::kGl) {
#ifdef DEFORMCD_HAS_GL
    // create_simulation made a GlSimulation for kGl.
    return std::make_unique<gl::GlContactResponse>(*context,
                                                   static_cast<gl::GlSimulation&>(simulation));
#else
    (void)context;
    throw GlError("this deformcd was built without the OpenGL backend (DEFORMCD_WITH_GL=OFF)");
#endif
  }
  return std::make_unique<cpu::CpuContactResponse>(*simulation.host_state(), std::move(executor));
}

}  // namespace deformcd
