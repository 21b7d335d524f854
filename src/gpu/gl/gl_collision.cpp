#include "gpu/gl/gl_collision.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "core/collision/broad_phase.h"
#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"
#include "deformcd/error.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/buffer_limit.h"
#include "gpu/gl/device_summary.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

// Fills a buffer with zero bytes on the GPU. Shader writes issued before must have landed: the
// caller issues GL_BUFFER_UPDATE_BARRIER_BIT first.
template <class T>
void clear_to_zero(const Ssbo<T>& buffer) {
  static_assert(sizeof(T) % 4 == 0, "cleared as 32-bit words");
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer.name()));
  DEFORMCD_GL_CHECK(glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER,
                                      GL_UNSIGNED_INT, nullptr));
}

std::uint32_t checked_mask_slots(std::uint32_t requested, std::uint32_t max_groups_z) {
  if (requested == 0) throw Error("GlCollisionOptions::mask_slots must be positive");
  return std::min(requested, max_groups_z);
}

std::uint32_t checked_check_interval(std::uint32_t passes) {
  if (passes == 0) throw Error("GlCollisionOptions::bvh_check_interval must be positive");
  return passes;
}

// The largest face count of the smaller mesh of any mesh pair.
std::uint32_t largest_query_mesh(const collision::CollisionData& data) {
  std::uint32_t most = 0;
  for (const gpu::BodyPair& pair : data.mesh_pairs) {
    most = std::max(most, std::min(data.meshes[pair.a].face_count, data.meshes[pair.b].face_count));
  }
  return most;
}

std::uint32_t largest_row_count(const std::vector<glm::uvec2>& box_rows) {
  std::uint32_t most = 0;
  for (const glm::uvec2& rows : box_rows)
    most = std::max(most, rows.y);
  return most;
}

}  // namespace

GlCollision::GlCollision(Context& context, const GlCollisionOptions& options,
                         std::shared_ptr<cpu::Executor> executor)
    : GlCollision(query_device_info(context), options, std::move(executor)) {}

GlCollision::GlCollision(const DeviceInfo& device, const GlCollisionOptions& options,
                         std::shared_ptr<cpu::Executor> executor)
    : device_info_(device),
      device_(device_summary(device)),
      max_buffer_bytes_(buffer_limit(device, options.max_buffer_bytes)),
      limit_is_device_(limit_is_device(device, options.max_buffer_bytes)),
      max_work_groups_(device.max_work_group_count),
      mask_slots_(checked_mask_slots(options.mask_slots, device.max_work_group_count[2])),
      initial_pair_capacity_(options.initial_pair_capacity),
      initial_candidate_capacity_(options.initial_candidate_capacity),
      initial_box_pair_capacity_(options.initial_box_pair_capacity),
      bvh_check_interval_(checked_check_interval(options.bvh_check_interval)),
      bb_update_("collision/bb_update.comp"),
      bb_collision_("collision/bb_collision.comp"),
      tri_tri_octree_("collision/tri_tri_octree.comp"),
      tri_tri_brute_("collision/tri_tri_brute.comp"),
      bb_pair_list_("collision/bb_pair_list.comp"),
      octree_candidates_("collision/octree_candidates.comp"),
      bvh_refit_("collision/bvh_refit.comp"),
      bvh_refit_level_("collision/bvh_refit_level.comp"),
      bvh_mesh_pairs_("collision/bvh_mesh_pairs.comp"),
      bvh_traverse_("collision/bvh_traverse.comp"),
      dispatch_args_("collision/dispatch_args.comp"),
      tri_tri_candidates_("collision/tri_tri_candidates.comp"),
      vertex_check_(device.max_work_group_count[0]),
      staging_({.max_block_bytes = device.max_ssbo_block_bytes,
                .max_gathered_bytes = max_buffer_bytes_,
                .limit_name = limit_name()}),
      executor_(std::move(executor)) {}

GlCollision::~GlCollision() = default;

void GlCollision::upload(const collision::CollisionData& data) {
  // Everything is checked before the first allocation, so a failed upload keeps the old state.
  check_collision_data(data);
  const CollisionCapacities capacities = initial_capacities(data);
  const std::vector<BufferSize> sizes = collision_buffer_sizes(data, capacities);
  check_buffer_sizes(sizes, max_buffer_bytes_, limit_name(), "GL collision");
  const auto box_count = static_cast<std::uint32_t>(gpu::kLeafBoxesPerBody * data.mesh_count());
  // The trees' reference quality on the positions they were built on: the current ones, if
  // every mesh has some yet (a read-back of GL sources, before anything changes).
  const bool positions_known = positions_cover(data.meshes);
  collision::BvhUpkeep upkeep =
      positions_known ? measured_bvh_upkeep(data) : collision::BvhUpkeep{};
  BvhWorkOrder order =
      plan_bvh_work_order(data.bvh_nodes, data.mesh_bvhs, data.meshes, data.faces.size());

  // The new buffers are all allocated before the old ones are released: if GL runs out of
  // memory, the GlError names the buffer and the previous state stays intact.
  const auto label = [&sizes](std::uint32_t binding) {
    return label_of(sizes, binding, "GL collision");
  };
  const auto copy = [&label](const auto& array, std::uint32_t binding) {
    return make_buffer(array, label(binding));
  };
  const std::vector<gpu::Box> empty_boxes(box_count, collision::empty_box());
  CollisionBuffers b{
      .boxes = copy(empty_boxes, gpu::kBoxInfo),
      .face_flags = allocate<std::uint32_t>(std::max<std::size_t>(data.faces.size(), 1),
                                            label(gpu::kCollisionResult)),
      .faces = copy(data.faces, gpu::kFaceInfo),
      .meshes = copy(data.meshes, gpu::kMeshInfo),
      .box_faces = copy(data.box_faces, gpu::kBoxFaceList),
      .face_pairs = allocate<gpu::FacePair>(capacities.face_pairs, label(gpu::kFacePair)),
      .box_mask = allocate<std::int32_t>(
          capacities.mask_slots * gpu::kLeafBoxesPerBody * gpu::kLeafBoxesPerBody,
          label(gpu::kBoxMask)),
      .face_boxes = copy(data.face_boxes, gpu::kFaceBoxes),
      .mesh_pairs = copy(data.mesh_pairs, gpu::kBodyPair),
      .counters = allocate<gpu::CollisionCounters>(1, label(gpu::kCollisionCounters)),
      .box_rows = copy(data.box_rows, gpu::kBoxRows),
      .bvh_nodes = copy(data.bvh_nodes, gpu::kBvhNode),
      .bvh_boxes =
          allocate<gpu::Box>(std::max<std::size_t>(data.bvh_nodes.size(), 1), label(gpu::kBvhBox)),
      .mesh_bvhs = copy(data.mesh_bvhs, gpu::kBodyBvh),
      .candidates = allocate<glm::uvec2>(capacities.candidates, label(gpu::kCandidatePair)),
      .dispatch_args = allocate<std::uint32_t>(kDispatchArgsWords, label(kDispatchArgsBinding)),
      .box_pair_list = allocate<glm::uvec2>(capacities.box_pairs, label(kBoxPairListBinding)),
      .bvh_levels = copy(order.refit_order, kBvhLevelsBinding),
      .touching_pairs = allocate<gpu::BodyPair>(std::max<std::size_t>(data.mesh_pairs.size(), 1),
                                                label(kTouchingPairsBinding)),
      .bvh_leaves = copy(order.leaves, kBvhLeavesBinding),
      .face_count = static_cast<std::uint32_t>(data.faces.size()),
      .box_count = box_count,
      .pair_capacity = static_cast<std::uint32_t>(capacities.face_pairs),
      .bvh_node_count = static_cast<std::uint32_t>(data.bvh_nodes.size()),
      .bvh_levels_ranges = std::move(order.levels),
      .candidate_capacity = static_cast<std::uint32_t>(capacities.candidates),
      .box_pair_capacity = static_cast<std::uint32_t>(capacities.box_pairs),
      .max_box_rows = largest_row_count(data.box_rows),
      .mesh_pair_count = static_cast<std::uint32_t>(data.mesh_pairs.size()),
      .max_query_faces = largest_query_mesh(data),
      .octree_chunks = plan_pair_chunks(data.mesh_pairs, data.meshes, mask_slots_,
                                        &gpu::MeshInfo::box_face_count),
      .brute_chunks = plan_pair_chunks(data.mesh_pairs, data.meshes, max_work_groups_[2],
                                       &gpu::MeshInfo::face_count),
  };
  check_dispatches(b);
  buffers_.emplace(std::move(b));
  meshes_ = data.meshes;
  staging_.set_labels(data.mesh_names);
  staging_.restart();  // the new mesh buffer needs the position words
  bb_update_.set_uniform("u_box_count", box_count);
  bvh_refit_.set_uniform("u_node_count", buffers_->bvh_node_count);
  bvh_mesh_pairs_.set_uniform("u_pair_count", buffers_->mesh_pair_count);
  set_capacity_uniforms(*buffers_);
  clear_to_zero(buffers_->face_flags);
  clear_to_zero(buffers_->counters);
  last_method_ = BroadPhase::kNone;
  pass_pending_ = false;
  lost_pass_.reset();
  bvh_passes_ = 0;
  upkeep_ = std::move(upkeep);
  upkeep_pending_.reset();
  if (!positions_known) upkeep_pending_.emplace(data);
  mesh_pairs_ = data.mesh_pairs;
  // The searches' per-face and per-pair tables are the old data's.
  proximity_.reset();
  host_proximity_.reset();
}

void GlCollision::set_positions(const std::vector<collision::PositionSource>& sources) {
  staging_.set_sources(sources);
}

std::vector<glm::vec3> GlCollision::read_positions(std::uint32_t mesh) {
  return staging_.read_source(mesh);
}

bool GlCollision::find_non_finite(std::uint32_t& mesh, std::uint32_t& vertex) {
  return vertex_check_.find(staging_, mesh, vertex);
}

void GlCollision::detect(BroadPhase method) {
  CollisionBuffers& b = buffers("detect");
  if (method != BroadPhase::kNone) {
    stage_positions(b);
    if (upkeep_pending_) {
      upkeep_ = measured_bvh_upkeep(*upkeep_pending_);
      upkeep_pending_.reset();
    }
  }
  last_method_ = method;
  pass_pending_ = true;
  lost_pass_.reset();
  run_pass(method, b);
}

void GlCollision::stage_positions(CollisionBuffers& b) {
  if (!staging_.stage(meshes_)) return;
  const PositionLayout& layout = staging_.layout();
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    meshes_[m].position_offset = layout.meshes[m].word_offset;
    meshes_[m].position_stride = layout.meshes[m].word_stride;
  }
  b.meshes.upload(std::span<const gpu::MeshInfo>(meshes_));
}

void GlCollision::run_pass(BroadPhase method, const CollisionBuffers& b) {
  if (method != BroadPhase::kNone) staging_.bind();
  b.bind();
  // The last pass's shader writes land before the clears; the callers' writes to their
  // position buffers before this pass reads them.
  memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  clear_to_zero(b.face_flags);
  clear_to_zero(b.counters);
  if (method == BroadPhase::kBvh) clear_to_zero(b.dispatch_args);  // the touching pairs' count
  run(method, b);
  // Downloads, the next pass and renderers reading the flags see this pass's results.
  memory_barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

bool GlCollision::positions_cover(const std::vector<gpu::MeshInfo>& meshes) const {
  const std::vector<collision::PositionSource>& sources = staging_.sources();
  if (sources.size() != meshes.size()) return false;
  for (std::size_t m = 0; m < sources.size(); ++m) {
    if (sources[m].kind == collision::PositionSource::Kind::kNone ||
        sources[m].vertex_count != meshes[m].vertex_count) {
      return false;
    }
  }
  return true;
}

collision::BvhUpkeep GlCollision::measured_bvh_upkeep(const collision::CollisionData& data) const {
  std::vector<std::vector<glm::vec3>> positions(data.mesh_count());
  std::vector<collision::MeshVertices> pose(data.mesh_count());
  for (std::uint32_t m = 0; m < data.mesh_count(); ++m) {
    positions[m] = staging_.read_source(m);
    pose[m] = {positions[m].empty() ? nullptr : &positions[m][0].x, 3u};
  }
  collision::BvhUpkeep upkeep;
  upkeep.reset(data, pose.data());
  return upkeep;
}

gpu::CollisionCounters GlCollision::counters() {
  complete_pass();
  require_results("counters");
  return buffers("counters").counters.download(0, 1).front();
}

void GlCollision::download_face_pairs(std::vector<gpu::FacePair>& out) {
  complete_pass();
  require_results("download_face_pairs");
  const CollisionBuffers& b = buffers("download_face_pairs");
  out = b.face_pairs.download(0, b.counters.download(0, 1).front().face_pairs);
}

void GlCollision::download_face_flags(std::vector<std::uint32_t>& out) {
  complete_pass();
  require_results("download_face_flags");
  const CollisionBuffers& b = buffers("download_face_flags");
  out = b.face_flags.download(0, b.face_count);
}

void GlCollision::download_boxes(std::vector<gpu::Box>& out) {
  complete_pass();
  require_results("download_boxes");
  const CollisionBuffers& b = buffers("download_boxes");
  out = b.boxes.download(0, b.box_count);
}

void GlCollision::download_bvh_boxes(std::vector<gpu::Box>& out) {
  complete_pass();
  require_results("download_bvh_boxes");
  const CollisionBuffers& b = buffers("download_bvh_boxes");
  out = b.bvh_boxes.download(0, b.bvh_node_count);
}

void GlCollision::download_bvh_nodes(std::vector<gpu::BvhNode>& out) {
  const CollisionBuffers& b = buffers("download_bvh_nodes");
  out = b.bvh_nodes.download(0, b.bvh_node_count);
}

void GlCollision::download_meshes(std::vector<gpu::MeshInfo>& out) {
  out = buffers("download_meshes").meshes.download(0, meshes_.size());
}

std::uint32_t GlCollision::gl_face_flag_buffer() const {
  return buffers_ ? buffers_->face_flags.name() : 0;
}

std::uint32_t GlCollision::gl_face_pair_buffer() const {
  return buffers_ ? buffers_->face_pairs.name() : 0;
}

std::uint32_t GlCollision::face_pair_capacity() const {
  return buffers_ ? buffers_->pair_capacity : 0;
}

std::uint32_t GlCollision::candidate_capacity() const {
  return buffers_ ? buffers_->candidate_capacity : 0;
}

std::uint32_t GlCollision::box_pair_capacity() const {
  return buffers_ ? buffers_->box_pair_capacity : 0;
}

bool GlCollision::positions_in_place() const {
  return staging_.staged() && staging_.layout().in_place();
}

CollisionBuffers& GlCollision::buffers(const char* operation) {
  if (!buffers_) throw Error(std::string("GlCollision::") + operation + " before upload()");
  return *buffers_;
}

std::string GlCollision::limit_name() const {
  return limit_is_device_ ? "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"
                          : "GlCollisionOptions::max_buffer_bytes";
}

std::uint64_t GlCollision::most_elements(std::uint64_t element_bytes) const {
  return std::min<std::uint64_t>(max_buffer_bytes_ / element_bytes,
                                 std::numeric_limits<std::uint32_t>::max());
}

CollisionCapacities GlCollision::initial_capacities(const collision::CollisionData& data) const {
  // A default never exceeds the limit (a given one may, and is then reported).
  const auto fit = [this](std::uint32_t given, std::uint64_t wanted, std::uint64_t bytes) {
    if (given > 0) return std::uint64_t{given};
    return std::clamp<std::uint64_t>(wanted, 1, std::max<std::uint64_t>(most_elements(bytes), 1));
  };
  const std::uint64_t faces = data.faces.size();
  CollisionCapacities c;
  // Room for every face in a few contacts; more only in deep interpenetration, which grows it.
  c.face_pairs =
      fit(initial_pair_capacity_, std::max<std::uint64_t>(1024, 4 * faces), sizeof(gpu::FacePair));
  c.mask_slots = std::clamp<std::uint64_t>(data.mesh_pairs.size(), 1, mask_slots_);
  // Candidates are face pairs whose boxes overlap: in contact, a few per face near the contact.
  c.candidates = fit(initial_candidate_capacity_, std::max<std::uint64_t>(4096, 16 * faces),
                     sizeof(glm::uvec2));
  // Every leaf-box pair of every mesh pair for two or three meshes; with more, a mesh seldom
  // touches all the others at once.
  const std::uint64_t box_pairs_per_mesh_pair =
      std::uint64_t{gpu::kLeafBoxesPerBody} * gpu::kLeafBoxesPerBody;
  c.box_pairs = fit(
      initial_box_pair_capacity_,
      box_pairs_per_mesh_pair * std::min<std::uint64_t>(data.mesh_pairs.size(), data.mesh_count()),
      sizeof(glm::uvec2));
  return c;
}

void GlCollision::check_dispatches(const CollisionBuffers& b) const {
  const auto check_x = [&](const ComputeProgram& program, std::uint32_t invocations,
                           const std::string& what) {
    const std::uint32_t groups = groups_covering(invocations, program.work_group_size()[0]);
    if (groups <= max_work_groups_[0]) return;
    throw GlError("GL collision: '" + program.shader_name() + "' would need " +
                  std::to_string(groups) + " work groups along x for " +
                  std::to_string(invocations) + " " + what +
                  ", more than the device's GL_MAX_COMPUTE_WORK_GROUP_COUNT of " +
                  std::to_string(max_work_groups_[0]));
  };
  check_x(bb_update_, b.box_count, "leaf boxes");
  check_x(bvh_refit_, b.bvh_node_count, "BVH nodes");
  // bb_collision.comp's z extents are the octree chunks': checked with tri_tri_octree.comp's.
  check_chunks_fit(tri_tri_octree_.shader_name(), b.octree_chunks,
                   tri_tri_octree_.work_group_size(), max_work_groups_);
  // bb_pair_list.comp runs over the brute chunks' z extents too, with x extents of 64 boxes.
  check_chunks_fit(tri_tri_brute_.shader_name(), b.brute_chunks, tri_tri_brute_.work_group_size(),
                   max_work_groups_);
  check_x(bvh_mesh_pairs_, b.mesh_pair_count, "mesh pairs");
  check_x(bvh_traverse_, b.max_query_faces, "faces of a query mesh");
  // The indirect dispatches clamp their lists' axis to the limit and loop; octree_candidates'
  // x covers the largest leaf box's rows.
  const std::uint32_t row_groups =
      groups_covering(b.max_box_rows, octree_candidates_.work_group_size()[0]);
  if (row_groups > max_work_groups_[0]) {
    throw GlError("GL collision: '" + octree_candidates_.shader_name() + "' would need " +
                  std::to_string(row_groups) + " work groups along x for a leaf box of " +
                  std::to_string(b.max_box_rows) +
                  " rows, more than the device's GL_MAX_COMPUTE_WORK_GROUP_COUNT of " +
                  std::to_string(max_work_groups_[0]));
  }
}

void GlCollision::set_capacity_uniforms(const CollisionBuffers& b) {
  tri_tri_octree_.set_uniform("u_pair_capacity", b.pair_capacity);
  tri_tri_brute_.set_uniform("u_pair_capacity", b.pair_capacity);
  tri_tri_candidates_.set_uniform("u_pair_capacity", b.pair_capacity);
  tri_tri_candidates_.set_uniform("u_candidate_capacity", b.candidate_capacity);
  bvh_traverse_.set_uniform("u_candidate_capacity", b.candidate_capacity);
  octree_candidates_.set_uniform("u_candidate_capacity", b.candidate_capacity);
  octree_candidates_.set_uniform("u_box_pair_capacity", b.box_pair_capacity);
  bb_pair_list_.set_uniform("u_box_pair_capacity", b.box_pair_capacity);
}

}  // namespace deformcd::gl
