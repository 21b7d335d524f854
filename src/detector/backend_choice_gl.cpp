// backend_choice.h's GL backend objects, in a build with the GL backend
// (src/detector/CMakeLists.txt compiles this file or backend_choice_none.cpp).
#include <memory>

#include "core/collision/collision_backend.h"
#include "core/collision/proximity.h"
#include "core/response/response_backend.h"
#include "core/sim/simulation_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "detector/backend_choice.h"
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_contact_response.h"
#include "gpu/gl/gl_proximity.h"
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

std::unique_ptr<collision::CollisionBackend> make_gl_collision(gl::Context& context) {
  return std::make_unique<gl::GlCollision>(context);
}

void GlProximityDeleter::operator()(gl::GlProximity* search) const {
  delete search;  // NOLINT(cppcoreguidelines-owning-memory): the unique_ptr's deleter
}

GlProximityPtr make_gl_proximity(gl::Context& context, const collision::CollisionData& data) {
  return GlProximityPtr(new gl::GlProximity(context, data));
}

bool is_gl_collision(const collision::CollisionBackend& backend) noexcept {
  return dynamic_cast<const gl::GlCollision*>(&backend) != nullptr;
}

std::vector<collision::ProximityCandidate> find_gl_proximity(
    collision::CollisionBackend& backend, gl::GlProximity& search, std::span<const float> reach,
    std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs) {
  const gl::ProximityRefitOrder order = dynamic_cast<gl::GlCollision&>(backend).prepare_proximity();
  return search.find_bound(order, reach, motion, mesh_pairs);
}

std::unique_ptr<sim::SimulationBackend> make_gl_simulation(gl::Context& context) {
  return std::make_unique<gl::GlSimulation>(context);
}

std::unique_ptr<response::ResponseBackend> make_gl_response(gl::Context& context,
                                                            sim::SimulationBackend& simulation) {
  // make_gl_simulation made a GlSimulation.
  return std::make_unique<gl::GlContactResponse>(context,
                                                 static_cast<gl::GlSimulation&>(simulation));
}

}  // namespace deformcd
