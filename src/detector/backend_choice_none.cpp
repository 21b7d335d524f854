// backend_choice.h's GL backend objects, in a build without the GL backend
// (-DDEFORMCD_WITH_GL=OFF; src/detector/CMakeLists.txt compiles this file or
// backend_choice_gl.cpp): none can be made.
#include <memory>

#include "core/collision/collision_backend.h"
#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/error.h"
#include "deformcd/gl/context.h"  // declarations only: fine without the GL backend
#include "detector/backend_choice.h"

namespace deformcd {

namespace {

[[noreturn]] void throw_built_without_gl() {
  throw GlError("this deformcd was built without the OpenGL backend (DEFORMCD_WITH_GL=OFF)");
}

}  // namespace

bool gl_backend_built() noexcept {
  return false;
}

std::unique_ptr<gl::Context> make_headless_gl_context() {
  throw_built_without_gl();
}

std::string gl_renderer(gl::Context& /*context*/) {
  throw_built_without_gl();
}

std::unique_ptr<collision::CollisionBackend> make_gl_collision(
    gl::Context& /*context*/, const std::shared_ptr<cpu::Executor>& /*executor*/) {
  throw_built_without_gl();
}

std::unique_ptr<sim::SimulationBackend> make_gl_simulation(gl::Context& /*context*/) {
  throw_built_without_gl();
}

std::unique_ptr<response::ResponseBackend> make_gl_response(
    gl::Context& /*context*/, sim::SimulationBackend& /*simulation*/) {
  throw_built_without_gl();
}

}  // namespace deformcd
