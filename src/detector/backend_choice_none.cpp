// backend_choice.h's GL backend objects, in a build without the GL backend
// (-DDEFORMCD_WITH_GL=OFF; src/detector/CMakeLists.txt compiles this file or
// backend_choice_gl.cpp): none can be made.
#include <memory>

#include "core/collision/collision_backend.h"
#include "core/collision/proximity.h"
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

std::unique_ptr<collision::CollisionBackend> make_gl_collision(gl::Context& /*context*/) {
  throw_built_without_gl();
}

void GlProximityDeleter::operator()(gl::GlProximity* /*search*/) const {
  // never made without the GL backend
}

GlProximityPtr make_gl_proximity(gl::Context& /*context*/,
                                 const collision::CollisionData& /*data*/) {
  throw_built_without_gl();
}

bool is_gl_collision(const collision::CollisionBackend& /*backend*/) noexcept {
  return false;
}

std::vector<collision::ProximityCandidate> find_gl_proximity(
    collision::CollisionBackend& /*backend*/, gl::GlProximity& /*search*/,
    std::span<const float> /*reach*/, std::span<const glm::vec3> /*motion*/,
    std::span<const std::uint32_t> /*mesh_pairs*/) {
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
