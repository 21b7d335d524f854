// backend_choice.h's GL backend objects, in a build with the GL backend
// (src/detector/CMakeLists.txt compiles this file or backend_choice_none.cpp).
#include <memory>

#include "core/collision/collision_backend.h"
#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "detector/backend_choice.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_contact_response.h"
#include "gpu/gl/gl_simulation.h"

namespace deformcd {

bool gl_backend_built() noexcept {
  return true;
}

std::unique_ptr<gl::Context> make_headless_gl_context() {
  return gl::create_headless_context();
}

std::string gl_renderer(gl::Context& context) {
  return gl::query_device_info(context).renderer;
}

std::unique_ptr<collision::CollisionBackend> make_gl_collision(
    gl::Context& context, const std::shared_ptr<cpu::Executor>& executor) {
  return std::make_unique<gl::GlCollision>(context, gl::GlCollisionOptions{}, executor);
}

std::unique_ptr<sim::SimulationBackend> make_gl_simulation(gl::Context& context) {
  return std::make_unique<gl::GlSimulation>(context);
}

std::unique_ptr<response::ResponseBackend> make_gl_response(gl::Context& context,
                                                            sim::SimulationBackend& simulation) {
  return std::make_unique<gl::GlContactResponse>(context, simulation);
}

}  // namespace deformcd
