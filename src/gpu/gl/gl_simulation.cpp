#include "gl_simulation.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <span>
#include <utility>

#include "buffer_from.h"
#include "buffer_limit.h"
#include "deformcd/error.h"
#include "deformcd/gl/device_info.h"
#include "device_summary.h"
#include "gl_check.h"
#include "simulation_upload_checks.h"

namespace deformcd::gl {

namespace {

// Each substep launches one invocation per element in a single 1D dispatch.
void check_fits_one_dispatch(const ComputeProgram& program, std::size_t invocations,
                             std::uint32_t max_work_groups) {
  const std::uint64_t most = std::uint64_t{max_work_groups} * program.work_group_size()[0];
  if (invocations > most) {
    throw GlError("GL simulation: '" + program.shader_name() + "' would need " +
                  std::to_string(invocations) + " invocations, more than one dispatch allows (" +
                  std::to_string(most) + ")");
  }
}

}  // namespace

GlSimulation::GlSimulation(Context& context, const GlSimulationOptions& options)
    : GlSimulation(query_device_info(context), options) {}

GlSimulation::GlSimulation(const DeviceInfo& device, const GlSimulationOptions& options)
    : device_(device_summary(device)),
      max_buffer_bytes_(buffer_limit(device, options.max_buffer_bytes)),
      limit_is_device_(limit_is_device(device, options.max_buffer_bytes)),
      max_work_groups_x_(device.max_work_group_count[0]),
      spring_update_("sim/spring_update.comp"),
      tet_update_("sim/tet_update.comp"),
      node_force_("sim/node_force.comp"),
      node_update_("sim/node_update.comp") {}

void GlSimulation::upload(const SimulationState& state) {
  // Everything is checked before the first allocation, so a failed upload keeps the old state.
  check_world_consistency(state);
  const std::vector<BufferSize> sizes = simulation_buffer_sizes(state);
  check_buffer_sizes(sizes, max_buffer_bytes_,
                     limit_is_device_ ? "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"
                                      : "GlSimulationOptions::max_buffer_bytes");
  check_fits_one_dispatch(spring_update_, state.springs.size(), max_work_groups_x_);
  check_fits_one_dispatch(tet_update_, state.tets.size(), max_work_groups_x_);
  check_fits_one_dispatch(node_force_, state.node_count(), max_work_groups_x_);
  check_fits_one_dispatch(node_update_, state.node_count(), max_work_groups_x_);

  // The new buffers are all allocated before the old ones are released: if GL runs out of
  // memory, the GlError names the buffer and the previous state stays intact.
  const auto copy = [&sizes](const auto& data, gpu::Binding binding) {
    return make_buffer(data, label_of(sizes, binding, "GL simulation"));
  };
  buffers_.emplace(SimulationBuffers{
      copy(state.positions, gpu::kNodePosition), copy(state.velocities, gpu::kNodeVelocity),
      copy(state.springs, gpu::kSpringInfo), copy(state.forces, gpu::kNodeForce),
      copy(state.body_params, gpu::kBodyParams), copy(state.node_body, gpu::kNodeBody),
      copy(state.spring_forces, gpu::kSpringForce),
      copy(state.node_spring_offset, gpu::kNodeSpringOffset),
      copy(state.node_spring_list, gpu::kNodeSpringList), copy(state.tets, gpu::kTetInfo),
      copy(state.tet_forces, gpu::kTetForce), copy(state.node_tet_offset, gpu::kNodeTetOffset),
      copy(state.node_tet_list, gpu::kNodeTetList), static_cast<std::uint32_t>(state.node_count()),
      static_cast<std::uint32_t>(state.springs.size()),
      static_cast<std::uint32_t>(state.tets.size()),
      static_cast<std::uint32_t>(state.body_params.size())});
  tet_update_.set_uniform("u_tet_count", buffers_->tet_count);
  spring_update_.set_uniform("u_spring_count", buffers_->spring_count);
  node_force_.set_uniform("u_node_count", buffers_->node_count);
  node_update_.set_uniform("u_node_count", buffers_->node_count);
}

void GlSimulation::substep(const sim::SubstepConstants& constants) {
  const SimulationBuffers& b = buffers("substep");
  b.positions.bind(gpu::kNodePosition);
  b.velocities.bind(gpu::kNodeVelocity);
  b.springs.bind(gpu::kSpringInfo);
  b.node_forces.bind(gpu::kNodeForce);
  b.body_params.bind(gpu::kBodyParams);
  b.node_body.bind(gpu::kNodeBody);
  b.spring_forces.bind(gpu::kSpringForce);
  b.node_spring_offset.bind(gpu::kNodeSpringOffset);
  b.node_spring_list.bind(gpu::kNodeSpringList);
  b.tets.bind(gpu::kTetInfo);
  b.tet_forces.bind(gpu::kTetForce);
  b.node_tet_offset.bind(gpu::kNodeTetOffset);
  b.node_tet_list.bind(gpu::kNodeTetList);

  spring_update_.dispatch_covering(b.spring_count);
  tet_update_.dispatch_covering(b.tet_count);
  storage_barrier();  // node_force reads the spring and tetrahedron forces
  node_force_.dispatch_covering(b.node_count);
  storage_barrier();  // node_update reads the node forces
  node_update_.set_uniform("u_h", constants.h);
  node_update_.set_uniform("u_gravity", constants.gravity);
  node_update_.set_uniform("u_velocity_decay", constants.velocity_decay);
  node_update_.dispatch_covering(b.node_count);
  // The next substep, the collision shaders and renderers drawing from SSBO 0 read positions.
  memory_barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void GlSimulation::finish() {
  DEFORMCD_GL_CHECK(glFinish());
}

void GlSimulation::download_positions(std::vector<glm::vec4>& out) {
  const SimulationBuffers& b = buffers("download_positions");
  out = b.positions.download(0, b.node_count);
}

void GlSimulation::download_velocities(std::vector<glm::vec4>& out) {
  const SimulationBuffers& b = buffers("download_velocities");
  out = b.velocities.download(0, b.node_count);
}

void GlSimulation::download_node_forces(std::vector<glm::vec4>& out) {
  const SimulationBuffers& b = buffers("download_node_forces");
  out = b.node_forces.download(0, b.node_count);
}

std::uint32_t GlSimulation::gl_position_buffer() const {
  return buffers_ ? buffers_->positions.name() : 0;
}

std::uint32_t GlSimulation::gl_velocity_buffer() const {
  return buffers_ ? buffers_->velocities.name() : 0;
}

const SimulationBuffers& GlSimulation::buffers(const char* operation) const {
  if (!buffers_) throw Error(std::string("GlSimulation::") + operation + " before upload()");
  return *buffers_;
}

}  // namespace deformcd::gl
