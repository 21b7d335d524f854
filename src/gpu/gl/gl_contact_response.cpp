#include "gpu/gl/gl_contact_response.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <span>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/buffer_limit.h"
#include "gpu/gl/contact_upload_checks.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/response_work_buffers.h"

namespace deformcd::gl {

namespace {

constexpr std::string_view kOwner = "GL contact response";

// Each pass launches one invocation per element in a single 1D dispatch.
void check_fits_one_dispatch(const ComputeProgram& program, std::size_t invocations,
                             std::uint32_t max_work_groups) {
  const std::uint64_t most = std::uint64_t{max_work_groups} * program.work_group_size()[0];
  if (invocations > most) {
    throw GlError(std::string(kOwner) + ": '" + program.shader_name() + "' would need " +
                  std::to_string(invocations) + " invocations, more than one dispatch allows (" +
                  std::to_string(most) + ")");
  }
}

// A buffer to replace `buffer` with when it holds fewer than `needed` elements (at least one:
// no binding is ever a zero-size buffer), else nothing. 1.5 x the need, within the limit, so
// that a contact set growing over a few frames reallocates rarely.
template <class T>
std::optional<Ssbo<T>> replacement(const std::optional<Ssbo<T>>& buffer, std::uint64_t needed,
                                   std::uint64_t max_bytes, const BufferLabel& label) {
  needed = std::max<std::uint64_t>(needed, 1u);
  if (buffer && buffer->size() >= needed) return std::nullopt;
  const std::uint64_t most = std::max<std::uint64_t>(max_bytes / sizeof(T), needed);
  return allocate<T>(std::min(needed + needed / 2u, most), label);
}

template <class T>
void adopt(std::optional<Ssbo<T>>& buffer, std::optional<Ssbo<T>>& grown) {
  if (grown) buffer = std::move(grown);
}

}  // namespace

GlContactResponse::GlContactResponse(Context& context, sim::SimulationBackend& simulation,
                                     const GlContactResponseOptions& options)
    : GlContactResponse(query_device_info(context), simulation, options) {}

GlContactResponse::GlContactResponse(const DeviceInfo& device, sim::SimulationBackend& simulation,
                                     const GlContactResponseOptions& options)
    : simulation_(simulation),
      max_buffer_bytes_(buffer_limit(device, options.max_buffer_bytes)),
      limit_is_device_(limit_is_device(device, options.max_buffer_bytes)),
      max_work_groups_x_(device.max_work_group_count[0]),
      frame_start_("response/contact_frame_start.comp"),
      deviation_("response/contact_deviation.comp"),
      activity_("response/contact_activity.comp"),
      compact_("response/contact_compact.comp"),
      count_("response/contact_count.comp"),
      dispatch_args_("response/contact_dispatch_args.comp"),
      sweep_("response/contact_sweep.comp"),
      slide_("response/contact_slide.comp"),
      residual_("response/contact_residual.comp"),
      stray_("response/contact_stray.comp") {
  dispatch_args_.set_uniform("u_residual_local_size", residual_.work_group_size()[0]);
  dispatch_args_.set_uniform("u_node_local_size", slide_.work_group_size()[0]);
}

void GlContactResponse::begin_frame(const response::FrameConstraints& constraints) {
  upload(constraints, false);
}

void GlContactResponse::update_frame(const response::FrameConstraints& constraints) {
  check_frame("update_frame");
  upload(constraints, true);
}

void GlContactResponse::upload(const response::FrameConstraints& constraints, bool keep_positions) {
  // Everything is checked, and every buffer that must grow allocated, before the first change:
  // a failure keeps the previous frame's constraints.
  const sim::NodeBuffers sim = gl_nodes(keep_positions ? "update_frame" : "begin_frame");
  const std::size_t first_volume = check_constraints_fit(constraints, sim.node_count);
  const response::NodeContactLists lists =
      response::index_constraints_by_node(sim.node_count, constraints.pairs);
  const std::vector<BufferSize> sizes = contact_buffer_sizes(constraints, sim.node_count);
  check_buffer_sizes(sizes, max_buffer_bytes_,
                     limit_is_device_ ? "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"
                                      : "GlContactResponseOptions::max_buffer_bytes",
                     kOwner);
  check_fits_one_dispatch(activity_, constraints.pairs.size(), max_work_groups_x_);
  for (const ComputeProgram* per_node : {&frame_start_, &deviation_, &count_, &slide_, &stray_})
    check_fits_one_dispatch(*per_node, sim.node_count, max_work_groups_x_);

  const std::uint64_t nodes = sim.node_count;
  const std::uint64_t pairs = constraints.pairs.size();
  const auto grow = [&](const auto& buffer, std::uint64_t needed, std::uint32_t binding) {
    return replacement(buffer, needed, max_buffer_bytes_, label_of(sizes, binding, kOwner));
  };
  auto new_pairs = grow(buffers_.pairs, pairs, gpu::kContactPair);
  auto new_slides = grow(buffers_.slides, pairs, gpu::kContactSlides);
  auto new_offset = grow(buffers_.node_offset, nodes + 1u, gpu::kNodeContactOffset);
  auto new_list = grow(buffers_.node_list, lists.list.size(), gpu::kNodeContactList);
  auto new_count = grow(buffers_.node_count, 2u * nodes, gpu::kNodeContactCount);
  auto new_start = grow(buffers_.frame_start, nodes, gpu::kFrameStart);
  auto new_motion = grow(buffers_.node_motion, nodes, gpu::kNodeMotion);
  auto new_projection_start = grow(buffers_.projection_start, nodes, gpu::kProjectionStart);
  auto new_impulses = grow(buffers_.impulses, 3u * pairs, gpu::kContactImpulse);
  auto new_slid = grow(buffers_.node_slid, nodes, gpu::kNodeSlid);
  auto new_guard = grow(buffers_.node_guard, nodes, gpu::kNodeGuard);
  auto new_acting = grow(buffers_.contact_acting, pairs, kContactActingBinding);
  auto new_acting_list = grow(buffers_.acting_list, pairs, kActingListBinding);
  auto new_active_slot = grow(buffers_.node_active_slot, lists.list.size(), kNodeActiveSlotBinding);
  auto new_touched = grow(buffers_.touched_node, nodes, kTouchedNodeBinding);
  auto new_state = grow(buffers_.state, kResponseStateWords, kResponseStateBinding);
  auto new_sweep_order = grow(buffers_.sweep_order, pairs, kSweepOrderBinding);
  auto new_sweep_colours = grow(buffers_.sweep_colours, pairs + 1u, kSweepColoursBinding);

  frame_ready_ = false;  // until the upload below has completed
  adopt(buffers_.pairs, new_pairs);
  adopt(buffers_.slides, new_slides);
  adopt(buffers_.node_offset, new_offset);
  adopt(buffers_.node_list, new_list);
  adopt(buffers_.node_count, new_count);
  adopt(buffers_.frame_start, new_start);
  adopt(buffers_.node_motion, new_motion);
  adopt(buffers_.projection_start, new_projection_start);
  adopt(buffers_.impulses, new_impulses);
  adopt(buffers_.contact_acting, new_acting);
  adopt(buffers_.acting_list, new_acting_list);
  adopt(buffers_.node_active_slot, new_active_slot);
  adopt(buffers_.touched_node, new_touched);
  adopt(buffers_.state, new_state);
  adopt(buffers_.sweep_order, new_sweep_order);
  adopt(buffers_.sweep_colours, new_sweep_colours);
  // The slide stamps outlive a window (a contact's slide goes on across searches): set only
  // where the buffer is new (or the nodes others), to a substep no projection has.
  if (new_slid.has_value() || node_count_ != sim.node_count) {
    adopt(buffers_.node_slid, new_slid);
    const std::vector<std::uint32_t> never(nodes, response::kNeverSlid);
    buffers_.node_slid->upload(std::span<const std::uint32_t>(never));
  }
  // The guard stamps: 0, which no projection has (they count from 1), where the buffer is new;
  // a stamp from an earlier projection is as good as none.
  if (new_guard.has_value()) {
    adopt(buffers_.node_guard, new_guard);
    const std::vector<std::uint32_t> none(buffers_.node_guard->size(), 0u);
    buffers_.node_guard->upload(std::span<const std::uint32_t>(none));
  }
  // Slides, impulses, counts, lists, the sweep's order and the state need no initial values:
  // each projection writes all it reads (a substep's first iteration resets the impulses).
  buffers_.pairs->upload(std::span<const gpu::ContactPair>(constraints.pairs));
  buffers_.node_offset->upload(std::span<const std::uint32_t>(lists.offset));
  buffers_.node_list->upload(std::span<const std::uint32_t>(lists.list));
  buffers_.node_motion->upload(std::span<const glm::vec4>(constraints.node_motion));

  constraints_ = &constraints;
  pair_count_ = static_cast<std::uint32_t>(pairs);
  first_volume_ = static_cast<std::uint32_t>(first_volume);
  node_count_ = sim.node_count;
  frame_positions_ = sim.gl_positions;
  compact_.set_uniform("u_pair_count", pair_count_);
  compact_.set_uniform("u_first_volume", first_volume_);
  count_.set_uniform("u_node_count", node_count_);
  count_.set_uniform("u_first_volume", first_volume_);
  stray_.set_uniform("u_node_count", node_count_);
  frame_start_.set_uniform("u_node_count", node_count_);
  frame_start_.set_uniform("u_keep_positions", keep_positions ? 1u : 0u);
  deviation_.set_uniform("u_node_count", node_count_);

  bind_storage_buffer(gpu::kNodePosition, sim.gl_positions);
  buffers_.node_motion->bind(gpu::kNodeMotion);
  buffers_.frame_start->bind(gpu::kFrameStart);
  frame_start_.dispatch_covering(node_count_);
  // The sweeps and the stray pass read the frame starts; the next substep overwrites the
  // positions read here.
  storage_barrier();
  frame_ready_ = true;
}

sim::NodeBuffers GlContactResponse::gl_nodes(const char* caller) const {
  const sim::NodeBuffers nodes = simulation_.node_buffers();
  if (nodes.gl_positions == 0 || nodes.gl_velocities == 0) {
    throw Error(std::string("GlContactResponse::") + caller +
                ": the simulation keeps no nodes in GL buffers (not uploaded yet, or not a GL "
                "simulation)");
  }
  return nodes;
}

void GlContactResponse::check_frame(const char* caller) const {
  if (!frame_ready_)
    throw Error(std::string("GlContactResponse::") + caller + " before begin_frame()");
  const sim::NodeBuffers sim = gl_nodes(caller);
  // A new upload allocates new buffers before releasing the old ones, so its positions buffer
  // has another name, and the frame starts recorded from the old one do not apply.
  if (sim.node_count != node_count_ || sim.gl_positions != frame_positions_) {
    throw Error(std::string("GlContactResponse::") + caller +
                ": the simulation was uploaded again since begin_frame(); begin a frame with "
                "constraints for its nodes first");
  }
}

bool GlContactResponse::project(const response::ContactConstants& k, int iterations) {
  check_frame("project");
  const sim::NodeBuffers sim = simulation_.node_buffers();
  // Bound on every call: other passes (the simulation, the collision detector) may have rebound
  // the points since.
  bind_storage_buffer(gpu::kNodePosition, sim.gl_positions);
  bind_storage_buffer(gpu::kNodeVelocity, sim.gl_velocities);
  buffers_.pairs->bind(gpu::kContactPair);
  buffers_.slides->bind(gpu::kContactSlides);
  buffers_.node_offset->bind(gpu::kNodeContactOffset);
  buffers_.node_list->bind(gpu::kNodeContactList);
  buffers_.node_count->bind(gpu::kNodeContactCount);
  buffers_.frame_start->bind(gpu::kFrameStart);
  buffers_.node_motion->bind(gpu::kNodeMotion);
  buffers_.projection_start->bind(gpu::kProjectionStart);
  buffers_.impulses->bind(gpu::kContactImpulse);
  buffers_.node_slid->bind(gpu::kNodeSlid);
  buffers_.node_guard->bind(gpu::kNodeGuard);
  buffers_.contact_acting->bind(kContactActingBinding);
  buffers_.acting_list->bind(kActingListBinding);
  buffers_.node_active_slot->bind(kNodeActiveSlotBinding);
  buffers_.touched_node->bind(kTouchedNodeBinding);
  buffers_.state->bind(kResponseStateBinding);
  buffers_.sweep_order->bind(kSweepOrderBinding);
  buffers_.sweep_colours->bind(kSweepColoursBinding);
  ++substep_;
  sweep_.set_uniform("u_substep", substep_);
  slide_.set_uniform("u_substep", substep_);
  // The stray and residual flags start cleared (the last projection's reads have waited for
  // every pass that wrote them).
  const std::uint32_t cleared[2] = {0u, 0u};
  buffers_.state->upload(std::span<const std::uint32_t>(cleared), kStrayFlagWord);
  static_assert(kResidualFlagWord == kStrayFlagWord + 1u);

  // Deviation, activity, compaction, count, then the sweep's order from the host and per
  // iteration the sweep (and after a last one the slide pass), each reading what the one before
  // wrote; the stray pass last. With no constraints only the stray pass runs: it watches every
  // free node's reach, as the CPU backend does.
  iterations_done_ = iterations;
  if (pair_count_ > 0) {
    // The constraint groups: the contacts, then the volume constraints (the list's last).
    const std::uint32_t group_begin[2] = {0u, first_volume_};
    const std::uint32_t group_end[2] = {first_volume_, pair_count_};
    deviation_.set_uniform("u_elapsed", k.elapsed);
    deviation_.set_uniform("u_h", k.h);
    deviation_.dispatch_covering(node_count_);
    storage_barrier();  // the activity pass reads the deviations
    // The contacts, then the volume constraints, which read the contacts' guard stamps.
    activity_.set_uniform("u_elapsed", k.elapsed);
    activity_.set_uniform("u_h", k.h);
    activity_.set_uniform("u_projection", substep_);
    for (std::uint32_t group = 0; group < 2u; ++group) {
      if (group_begin[group] == group_end[group]) continue;
      activity_.set_uniform("u_pair_begin", group_begin[group]);
      activity_.set_uniform("u_pair_end", group_end[group]);
      activity_.dispatch_covering(group_end[group] - group_begin[group]);
      storage_barrier();  // the volume constraints read the stamps, the compaction the flags
    }
    compact_.dispatch(1);
    storage_barrier();  // the count pass reads the acting places and the cleared touched count
    count_.dispatch_covering(node_count_);
    storage_barrier();  // the arguments are the counts
    dispatch_args_.dispatch(1);
    command_barrier();  // the indirect dispatches read the arguments

    // The sweep's colours, made on the host from the acting list (download() waits for the
    // passes that wrote it): the CPU backend's function on the same list, so the same order.
    const std::vector<std::uint32_t> counts =
        buffers_.state->download(kActingContactsWord, kActingTotalWord + 1u);
    const std::vector<std::uint32_t> acting = buffers_.acting_list->download(0, counts[1]);
    sweep_order_.colour(constraints_->pairs, acting, counts[0], constraints_->window_start);
    const std::vector<std::uint32_t>& colour_begin = sweep_order_.colour_begin();
    if (!acting.empty()) {
      buffers_.sweep_order->upload(std::span<const std::uint32_t>(sweep_order_.order()));
      buffers_.sweep_colours->upload(std::span<const std::uint32_t>(colour_begin));
    }
    sweep_.set_uniform("u_colours", static_cast<std::uint32_t>(colour_begin.size() - 1u));
    sweep_.set_uniform("u_contact_colours", sweep_order_.contact_colours());
    sweep_.set_uniform("u_h", k.h);
    sweep_.set_uniform("u_friction_static", k.friction_static);
    sweep_.set_uniform("u_friction_dynamic", k.friction_dynamic);
    sweep_.set_uniform("u_restitution", k.restitution);
    sweep_.set_uniform("u_max_untangle_step", k.max_untangle_step);
    // `last`: the friction's last-iteration rule applies, and the slide pass stamps after it.
    const auto iterate = [&](bool first_iteration, bool last) {
      sweep_.set_uniform("u_first_iteration", static_cast<std::uint32_t>(first_iteration));
      sweep_.set_uniform("u_last_iteration", static_cast<std::uint32_t>(last));
      sweep_.dispatch(1);
      storage_barrier();  // the next sweep, the slide and residual passes read the nodes
      if (!last) return;
      slide_.dispatch_indirect(buffers_.state->name(), kSlidePassArgsWord);
      storage_barrier();  // the next sweep reads the stamps
    };
    for (int iteration = 0; iteration < iterations; ++iteration)
      iterate(iteration == 0, iteration + 1 == iterations);
    // More while the sweeps have not converged (the residual pass's flag, read back), to
    // kMaxIterationFactor x the iterations asked.
    while (iterations_done_ < response::kMaxIterationFactor * iterations) {
      residual_.dispatch_indirect(buffers_.state->name(), kResidualArgsWord);
      // download() puts the barrier that makes the pass's write visible to it.
      if (buffers_.state->download(kResidualFlagWord, 1)[0] == 0u) break;
      buffers_.state->upload(std::span<const std::uint32_t>(cleared, 1), kResidualFlagWord);
      iterate(false, true);
      ++iterations_done_;
    }
  }
  stray_.set_uniform("u_elapsed", k.elapsed);
  stray_.dispatch_covering(node_count_);
  // The next substep (and the next projection's passes), the collision shaders and renderers
  // drawing from SSBO 0 read the corrected nodes.
  memory_barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                 GL_BUFFER_UPDATE_BARRIER_BIT);
  // The stray flag: a projection's second wait, after the acting list's (a new search must
  // start before the next substep when it is set).
  return buffers_.state->download(kStrayFlagWord, 1)[0] != 0u;
}

std::vector<glm::vec4> GlContactResponse::download_frame_start() const {
  if (!frame_ready_) throw Error("GlContactResponse::download_frame_start before begin_frame()");
  return buffers_.frame_start->download(0, node_count_);
}

}  // namespace deformcd::gl
