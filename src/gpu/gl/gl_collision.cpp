#include "gl_collision.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include "collision_upload_checks.h"
#include "core/collision/broad_phase.h"
#include "deformcd/error.h"
#include "gl_check.h"

namespace deformcd::gl {

namespace {

// A buffer of at least one element: binding a zero-size buffer is an error on some drivers,
// and an empty world still dispatches nothing that would read the placeholder.
template <class T>
Ssbo<T> make_buffer(const std::vector<T>& data) {
  Ssbo<T> buffer(std::max<std::size_t>(data.size(), 1));
  buffer.upload(std::span<const T>(data));
  return buffer;
}

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

// Dispatches `program` over a chunk: x and y cover the chunk's largest counts, z its pairs.
void dispatch_chunk(ComputeProgram& program, const PairChunk& chunk) {
  const std::array<std::uint32_t, 3>& local = program.work_group_size();
  const std::uint32_t groups_x = groups_covering(chunk.max_a, local[0]);
  const std::uint32_t groups_y = groups_covering(chunk.max_b, local[1]);
  if (groups_x == 0 || groups_y == 0) return;
  program.set_uniform("u_pair_first", chunk.first);
  program.dispatch(groups_x, groups_y, chunk.count);
}

}  // namespace

GlCollision::GlCollision(Context& context, const GlSimulation& simulation,
                         const GlCollisionOptions& options)
    : GlCollision(query_device_info(context), simulation, options) {}

GlCollision::GlCollision(const DeviceInfo& device, const GlSimulation& simulation,
                         const GlCollisionOptions& options)
    : simulation_(simulation),
      max_buffer_bytes_(options.max_buffer_bytes > 0
                            ? std::min(options.max_buffer_bytes, device.max_ssbo_block_bytes)
                            : device.max_ssbo_block_bytes),
      limit_is_device_(options.max_buffer_bytes == 0 ||
                       options.max_buffer_bytes >= device.max_ssbo_block_bytes),
      max_work_groups_(device.max_work_group_count),
      mask_slots_(checked_mask_slots(options.mask_slots, device.max_work_group_count[2])),
      initial_pair_capacity_(options.initial_pair_capacity),
      bb_update_("collision/bb_update.comp"),
      bb_collision_("collision/bb_collision.comp"),
      tri_tri_octree_("collision/tri_tri_octree.comp"),
      tri_tri_brute_("collision/tri_tri_brute.comp") {}

void GlCollision::upload(const WorldState& state) {
  // Everything is checked before the first allocation, so a failed upload keeps the old state.
  check_collision_consistency(state);
  const std::uint64_t capacity = initial_capacity(state);
  const std::uint64_t slots = std::clamp<std::uint64_t>(state.body_pairs.size(), 1, mask_slots_);
  check_buffer_sizes(collision_buffer_sizes(state, capacity, slots), max_buffer_bytes_,
                     limit_name(), "GL collision");
  const auto box_count = static_cast<std::uint32_t>(gpu::kLeafBoxesPerBody * state.body_count());
  std::vector<PairChunk> octree_chunks = plan_pair_chunks(
      state.body_pairs, state.objects, mask_slots_, &gpu::ObjectInfo::box_face_count);
  std::vector<PairChunk> brute_chunks = plan_pair_chunks(
      state.body_pairs, state.objects, max_work_groups_[2], &gpu::ObjectInfo::face_count);
  check_dispatches(box_count, octree_chunks, brute_chunks);

  // The new buffers are all allocated before the old ones are released: if GL runs out of
  // memory (GlError from BufferObject), the previous state stays intact.
  const std::vector<gpu::Box> empty_boxes(box_count, collision::empty_box());
  buffers_.emplace(CollisionBuffers{
      .boxes = make_buffer(empty_boxes),
      .face_flags = Ssbo<std::uint32_t>(std::max<std::size_t>(state.faces.size(), 1)),
      .faces = make_buffer(state.faces),
      .objects = make_buffer(state.objects),
      .box_faces = make_buffer(state.box_faces),
      .face_pairs = Ssbo<gpu::FacePair>(capacity),
      .box_mask = Ssbo<std::int32_t>(slots * gpu::kLeafBoxesPerBody * gpu::kLeafBoxesPerBody),
      .face_boxes = make_buffer(state.face_boxes),
      .body_pairs = make_buffer(state.body_pairs),
      .counters = Ssbo<gpu::CollisionCounters>(1),
      .box_rows = make_buffer(state.box_rows),
      .node_count = static_cast<std::uint32_t>(state.node_count()),
      .face_count = static_cast<std::uint32_t>(state.faces.size()),
      .box_count = box_count,
      .pair_capacity = static_cast<std::uint32_t>(capacity),
      .octree_chunks = std::move(octree_chunks),
      .brute_chunks = std::move(brute_chunks),
  });
  bb_update_.set_uniform("u_box_count", box_count);
  set_pair_capacity_uniforms(buffers_->pair_capacity);
  clear_to_zero(buffers_->face_flags);
  clear_to_zero(buffers_->counters);
  last_method_ = BroadPhase::kNone;
}

void GlCollision::detect(BroadPhase method) {
  const CollisionBuffers& b = buffers("detect");
  bind_positions(b);
  b.bind();
  memory_barrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the last pass's shader writes land first
  clear_to_zero(b.face_flags);
  clear_to_zero(b.counters);
  last_method_ = method;
  switch (method) {
    case BroadPhase::kNone:
      break;
    case BroadPhase::kOctree:
      run_octree(b);
      break;
    case BroadPhase::kBrute:
      run_brute(b);
      break;
  }
  // Downloads, the next pass and renderers reading the flags see this pass's results.
  memory_barrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

void GlCollision::run_octree(const CollisionBuffers& b) {
  bb_update_.dispatch_covering(b.box_count);
  storage_barrier();  // bb_collision reads the boxes
  const std::array<std::uint32_t, 3>& local = bb_collision_.work_group_size();
  for (const PairChunk& chunk : b.octree_chunks) {
    bb_collision_.set_uniform("u_pair_first", chunk.first);
    bb_collision_.dispatch(groups_covering(gpu::kLeafBoxesPerBody, local[0]),
                           groups_covering(gpu::kLeafBoxesPerBody, local[1]), chunk.count);
    storage_barrier();  // the narrow phase reads the masks
    dispatch_chunk(tri_tri_octree_, chunk);
    storage_barrier();  // the next chunk's bb_collision rewrites the mask slots read here
  }
}

void GlCollision::run_brute(const CollisionBuffers& b) {
  for (const PairChunk& chunk : b.brute_chunks)
    dispatch_chunk(tri_tri_brute_, chunk);
}

gpu::CollisionCounters GlCollision::counters() {
  return buffers("counters").counters.download(0, 1).front();
}

void GlCollision::download_face_pairs(std::vector<gpu::FacePair>& out) {
  CollisionBuffers& b = buffers("download_face_pairs");
  gpu::CollisionCounters found = counters();
  // A pass is deterministic in what it finds (only the slots' order varies), so one rerun on
  // the same positions fills the grown buffer; the bound guards against a changed state.
  for (int rerun = 0; found.face_pairs > b.pair_capacity; ++rerun) {
    if (rerun == 2) {
      throw Error("GlCollision::download_face_pairs: the pass found " +
                  std::to_string(found.face_pairs) + " face pairs after " + std::to_string(rerun) +
                  " reruns with room for " + std::to_string(b.pair_capacity) +
                  " (did the positions change?)");
    }
    grow_face_pairs(b, found.face_pairs);
    detect(last_method_);
    found = counters();
  }
  out = b.face_pairs.download(0, found.face_pairs);
}

void GlCollision::download_face_flags(std::vector<std::uint32_t>& out) {
  const CollisionBuffers& b = buffers("download_face_flags");
  out = b.face_flags.download(0, b.face_count);
}

void GlCollision::download_boxes(std::vector<gpu::Box>& out) {
  const CollisionBuffers& b = buffers("download_boxes");
  out = b.boxes.download(0, b.box_count);
}

std::uint32_t GlCollision::gl_face_flag_buffer() const {
  return buffers_ ? buffers_->face_flags.name() : 0;
}

std::uint32_t GlCollision::face_pair_capacity() const {
  return buffers_ ? buffers_->pair_capacity : 0;
}

CollisionBuffers& GlCollision::buffers(const char* operation) {
  if (!buffers_) throw Error(std::string("GlCollision::") + operation + " before upload()");
  return *buffers_;
}

std::string_view GlCollision::limit_name() const {
  return limit_is_device_ ? "the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE"
                          : "GlCollisionOptions::max_buffer_bytes";
}

std::uint64_t GlCollision::initial_capacity(const WorldState& state) const {
  if (initial_pair_capacity_ > 0) return initial_pair_capacity_;
  // Room for every face in a few contacts; more only in deep interpenetration, which grows it.
  const std::uint64_t wanted = std::max<std::uint64_t>(1024, 4 * std::uint64_t{state.faces.size()});
  const std::uint64_t most = max_buffer_bytes_ / sizeof(gpu::FacePair);
  return std::clamp<std::uint64_t>(wanted, 1, std::max<std::uint64_t>(most, 1));
}

void GlCollision::check_dispatches(std::uint32_t box_count,
                                   const std::vector<PairChunk>& octree_chunks,
                                   const std::vector<PairChunk>& brute_chunks) const {
  const std::uint32_t box_groups = groups_covering(box_count, bb_update_.work_group_size()[0]);
  if (box_groups > max_work_groups_[0]) {
    throw GlError("GL collision: '" + bb_update_.shader_name() + "' would need " +
                  std::to_string(box_groups) + " work groups along x for " +
                  std::to_string(box_count) +
                  " leaf boxes, more than the device's GL_MAX_COMPUTE_WORK_GROUP_COUNT of " +
                  std::to_string(max_work_groups_[0]));
  }
  // bb_collision.comp's z extents are the octree chunks': checked with tri_tri_octree.comp's.
  check_chunks_fit(tri_tri_octree_.shader_name(), octree_chunks, tri_tri_octree_.work_group_size(),
                   max_work_groups_);
  check_chunks_fit(tri_tri_brute_.shader_name(), brute_chunks, tri_tri_brute_.work_group_size(),
                   max_work_groups_);
}

void GlCollision::bind_positions(const CollisionBuffers& b) const {
  const std::uint32_t positions = simulation_.gl_position_buffer();
  if (positions == 0) {
    throw Error("GlCollision::detect: the simulation holds no positions (upload the world to it)");
  }
  // The shaders index positions by the faces' nodes: the buffer must hold them all.
  GLint64 bytes = 0;
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, positions));
  DEFORMCD_GL_CHECK(glGetBufferParameteri64v(GL_SHADER_STORAGE_BUFFER, GL_BUFFER_SIZE, &bytes));
  const std::uint64_t needed = std::uint64_t{b.node_count} * sizeof(glm::vec4);
  if (static_cast<std::uint64_t>(bytes) < needed) {
    throw Error("GlCollision::detect: the simulation holds " + std::to_string(bytes) +
                " bytes of positions, but the uploaded faces need " + std::to_string(b.node_count) +
                " nodes (" + std::to_string(needed) + " bytes)");
  }
  DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kNodePosition, positions));
}

void GlCollision::set_pair_capacity_uniforms(std::uint32_t capacity) {
  tri_tri_octree_.set_uniform("u_pair_capacity", capacity);
  tri_tri_brute_.set_uniform("u_pair_capacity", capacity);
}

void GlCollision::grow_face_pairs(CollisionBuffers& b, std::uint32_t pairs) {
  const std::uint64_t most = std::min<std::uint64_t>(max_buffer_bytes_ / sizeof(gpu::FacePair),
                                                     std::numeric_limits<std::uint32_t>::max());
  if (pairs > most) {
    throw GlError("GL collision: a pass found " + std::to_string(pairs) +
                  " intersecting face pairs, more than Face Pair (SSBO 10) can hold under " +
                  std::string(limit_name()) + " (" + std::to_string(max_buffer_bytes_) +
                  " bytes: " + std::to_string(most) + " pairs of " +
                  std::to_string(sizeof(gpu::FacePair)) + " bytes)");
  }
  // Half again as many: a few more contacts next frame do not cost another rerun.
  const std::uint64_t capacity = std::min<std::uint64_t>(most, pairs + pairs / 2);
  b.face_pairs = Ssbo<gpu::FacePair>(capacity);
  b.pair_capacity = static_cast<std::uint32_t>(capacity);
  set_pair_capacity_uniforms(b.pair_capacity);
}

}  // namespace deformcd::gl
