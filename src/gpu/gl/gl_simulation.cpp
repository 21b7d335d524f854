#include "gpu/gl/gl_simulation.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <span>
#include <utility>

#include "core/sim/node_force_lists.h"
#include "deformcd/error.h"
#include "deformcd/gl/device_info.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/buffer_limit.h"
#include "gpu/gl/device_summary.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/simulation_upload_checks.h"

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
      edge_update_("sim/edge_update.comp"),
      tet_update_("sim/tet_update.comp"),
      node_update_("sim/node_update.comp") {}

void GlSimulation::upload(const SimulationState& state) {
  // Everything is checked before the first allocation, so a failed upload keeps the old state.
  check_world_consistency(state);
  const sim::SpringEdges edges = sim::build_spring_edges(state);
  const sim::TetCorners corners = sim::build_tet_corners(state);
  const std::vector<BufferSize> sizes = simulation_buffer_sizes(state, edges, corners);
  check_buffer_sizes(sizes, max_buffer_bytes_,
                     limit_is_device_ ? "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"
                                      : "GlSimulationOptions::max_buffer_bytes");
  check_fits_one_dispatch(edge_update_, edges.size(), max_work_groups_x_);
  check_fits_one_dispatch(tet_update_, corners.tets.size(), max_work_groups_x_);
  check_fits_one_dispatch(node_update_, state.node_count(), max_work_groups_x_);

  // The edges as the shaders read them (one struct per edge; the CPU keeps one array per field).
  std::vector<gpu::SpringEdge> edge_info(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    edge_info[e] = {edges.a[e], edges.b[e], edges.rest_length[e], edges.damping[e]};
  std::vector<glm::uvec4> corner_slots(corners.tets.size());
  for (std::size_t t = 0; t < corners.tets.size(); ++t) {
    corner_slots[t] = {corners.corner_slot[4 * t], corners.corner_slot[4 * t + 1],
                       corners.corner_slot[4 * t + 2], corners.corner_slot[4 * t + 3]};
  }
  // Every slot starts at zero; a slot no node lists is written and never read.
  const std::vector<glm::vec4> corner_forces(corners.slot_count, glm::vec4(0.0f));
  const std::vector<glm::vec4> edge_states(edges.size(), glm::vec4(0.0f));
  // No body is frozen before its first substep (a state's own BodyParams::frozen is not read).
  std::vector<gpu::BodyParams> body_params = state.body_params;
  for (gpu::BodyParams& p : body_params)
    p.frozen = 0.0f;

  // The new buffers are all allocated before the old ones are released: if GL runs out of
  // memory, the GlError names the buffer and the previous state stays intact.
  const auto copy = [&sizes](const auto& data, gpu::Binding binding) {
    return make_buffer(data, label_of(sizes, binding, "GL simulation"));
  };
  buffers_.emplace(SimulationBuffers{
      copy(state.positions, gpu::kNodePosition), copy(state.velocities, gpu::kNodeVelocity),
      copy(edge_info, gpu::kSpringEdge), copy(state.forces, gpu::kNodeForce),
      copy(body_params, gpu::kBodyParams), copy(state.node_body, gpu::kNodeBody),
      copy(edge_states, gpu::kEdgeState), copy(edges.node_offset, gpu::kNodeEdgeOffset),
      copy(edges.node_terms, gpu::kNodeEdgeTerm), copy(corners.tets, gpu::kTetInfo),
      copy(corner_forces, gpu::kCornerForce), copy(corners.node_offset, gpu::kNodeCornerOffset),
      copy(corner_slots, gpu::kTetCornerSlot), static_cast<std::uint32_t>(state.node_count()),
      static_cast<std::uint32_t>(edges.size()), static_cast<std::uint32_t>(corners.tets.size()),
      static_cast<std::uint32_t>(state.body_params.size())});
  edge_update_.set_uniform("u_edge_count", buffers_->edge_count);
  tet_update_.set_uniform("u_tet_count", buffers_->tet_count);
  node_update_.set_uniform("u_node_count", buffers_->node_count);
  frozen_ = sim::FrozenBodies(state);
  body_params_ = std::move(body_params);
}

void GlSimulation::upload_frozen() {
  for (std::size_t b = 0; b < body_params_.size(); ++b)
    body_params_[b].frozen = frozen_.frozen(static_cast<std::uint32_t>(b)) ? 1.0f : 0.0f;
  buffers_->body_params.upload(std::span<const gpu::BodyParams>(body_params_), 0);
}

void GlSimulation::substep(const sim::SubstepConstants& constants) {
  const SimulationBuffers& b = buffers("substep");
  b.positions.bind(gpu::kNodePosition);
  b.velocities.bind(gpu::kNodeVelocity);
  b.edges.bind(gpu::kSpringEdge);
  b.node_forces.bind(gpu::kNodeForce);
  b.body_params.bind(gpu::kBodyParams);
  b.node_body.bind(gpu::kNodeBody);
  b.edge_states.bind(gpu::kEdgeState);
  b.node_edge_offset.bind(gpu::kNodeEdgeOffset);
  b.node_edge_terms.bind(gpu::kNodeEdgeTerm);
  b.tets.bind(gpu::kTetInfo);
  b.corner_forces.bind(gpu::kCornerForce);
  b.node_corner_offset.bind(gpu::kNodeCornerOffset);
  b.tet_corner_slots.bind(gpu::kTetCornerSlot);

  edge_update_.dispatch_covering(b.edge_count);
  tet_update_.dispatch_covering(b.tet_count);
  storage_barrier();  // node_update reads the edge states and the corner forces
  node_update_.set_uniform("u_h", constants.h);
  node_update_.set_uniform("u_gravity", constants.gravity);
  node_update_.set_uniform("u_velocity_decay", constants.velocity_decay);
  node_update_.dispatch_covering(b.node_count);
  // The next substep, the collision shaders and renderers drawing from SSBO 0 read positions.
  memory_barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
  if (frozen_.after_substep()) upload_frozen();
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

void GlSimulation::set_inverse_masses(std::uint32_t first, std::span<const float> inverse_mass) {
  if (!buffers_) throw Error("GlSimulation::set_inverse_masses before upload()");
  SimulationBuffers& b = *buffers_;
  sim::check_node_range(first, inverse_mass.size(), b.node_count);
  // The positions' xyz go back as they were read: only the w changes.
  std::vector<glm::vec4> positions = b.positions.download(first, inverse_mass.size());
  for (std::size_t k = 0; k < inverse_mass.size(); ++k)
    positions[k].w = inverse_mass[k];
  b.positions.upload(std::span<const glm::vec4>(positions), first);
  const std::vector<glm::vec4> still(inverse_mass.size(), glm::vec4(0.0f));
  b.velocities.upload(std::span<const glm::vec4>(still), first);
  if (frozen_.set_inverse_masses(first, inverse_mass)) upload_frozen();
}

void GlSimulation::download_node_forces(std::vector<glm::vec4>& out) {
  const SimulationBuffers& b = buffers("download_node_forces");
  out = b.node_forces.download(0, b.node_count);
}

sim::NodeBuffers GlSimulation::node_buffers() {
  if (!buffers_) return {};
  return {.node_count = buffers_->node_count,
          .gl_positions = buffers_->positions.name(),
          .gl_velocities = buffers_->velocities.name()};
}

const SimulationBuffers& GlSimulation::buffers(const char* operation) const {
  if (!buffers_) throw Error(std::string("GlSimulation::") + operation + " before upload()");
  return *buffers_;
}

}  // namespace deformcd::gl
