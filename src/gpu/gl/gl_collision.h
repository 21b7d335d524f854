#pragma once
// Collision detection on the GPU: the paper's compute shaders 0 (BBUpdate), 1 (BBCollision) and
// 2 (Triangle-Triangle Intersection) over the positions a GlSimulation holds, and the paper's
// all-pairs baseline, for every pair of different bodies. Same pairs as the CPU backend
// (src/cpu/cpu_collision.*), which runs the same algorithm on the same floats.
//
// One pass (detect):
//   reset    face flags (SSBO 5) and counters (SSBO 23) cleared with glClearBufferData;
//   octree   bb_update.comp: one invocation per leaf box of every body (64 x bodies, work
//            groups of 4 as in the paper) recomputes the box from its faces' vertices; then for
//            each chunk of at most mask_slots body pairs, bb_collision.comp (64 x 64 x chunk)
//            fills one 64 x 64 mask slot per pair, and tri_tri_octree.comp (N' x M' x chunk, the
//            chunk's largest row counts) tests the row pairs whose boxes overlap, each face pair
//            from the first overlapping box pair listing both faces only;
//   brute    tri_tri_brute.comp (N x M x chunk) tests every face pair.
// Intersecting pairs go to SSBO 10 at slots taken with atomicAdd; when they overflow its
// capacity, download_face_pairs grows it and reruns the pass.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "collision_buffers.h"
#include "compute_program.h"
#include "core/collision/collision_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "gl_simulation.h"

namespace deformcd::gl {

struct GlCollisionOptions {
  // Largest buffer upload() accepts, in bytes. 0: the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  std::uint64_t max_buffer_bytes = 0;
  // Body pairs per octree chunk, each taking one 64 x 64 int mask slot (16 KiB): the mask's
  // memory is min(mask_slots, body pairs) x 16 KiB, whatever the number of bodies. Must be
  // positive; capped at the device's z work-group count.
  std::uint32_t mask_slots = 64;
  // Face-pair slots (SSBO 10, 48 bytes each) allocated by upload(). 0: max(1024, 4 x faces),
  // capped at what the buffer limit allows. The buffer grows (x 1.5 the count) when a pass finds
  // more pairs.
  std::uint32_t initial_pair_capacity = 0;
};

class GlCollision final : public collision::CollisionBackend {
 public:
  // Makes `context` current and compiles the four shaders (GlError if that fails). The context
  // and `simulation` must outlive this object; the context must be current on the calling thread
  // for every call, destruction included. Throws Error when options.mask_slots is 0.
  GlCollision(Context& context, const GlSimulation& simulation,
              const GlCollisionOptions& options = {});

  [[nodiscard]] std::string_view name() const override { return "gl"; }
  // Checks the collision lists (Error when inconsistent), the buffer sizes (GlError naming every
  // buffer over the limit, with its size and the limit) and the dispatch sizes (GlError naming
  // the shader) before allocating anything, then replaces the buffers; the previous ones are
  // kept when it throws. Flags and counters start at 0, the boxes empty.
  void upload(const WorldState& state) override;
  // One pass over the simulation's current positions (SSBO 0, bound here). kNone only resets
  // the flags and counters. Throws Error before upload(), or when the simulation holds fewer
  // nodes than the faces index.
  void detect(BroadPhase method) override;
  [[nodiscard]] gpu::CollisionCounters counters() override;
  void download_face_pairs(std::vector<gpu::FacePair>& out) override;
  void download_face_flags(std::vector<std::uint32_t>& out) override;
  void download_boxes(std::vector<gpu::Box>& out) override;
  [[nodiscard]] std::uint32_t gl_face_flag_buffer() const override;

  // Face-pair slots in SSBO 10 now (0 before upload()).
  [[nodiscard]] std::uint32_t face_pair_capacity() const;

 private:
  GlCollision(const DeviceInfo& device, const GlSimulation& simulation,
              const GlCollisionOptions& options);
  CollisionBuffers& buffers(const char* operation);
  [[nodiscard]] std::string_view limit_name() const;
  [[nodiscard]] std::uint64_t initial_capacity(const WorldState& state) const;
  // Throws GlError naming the first shader whose dispatch would exceed the device's limits.
  void check_dispatches(std::uint32_t box_count, const std::vector<PairChunk>& octree_chunks,
                        const std::vector<PairChunk>& brute_chunks) const;
  void bind_positions(const CollisionBuffers& b) const;
  void set_pair_capacity_uniforms(std::uint32_t capacity);
  void run_octree(const CollisionBuffers& b);
  void run_brute(const CollisionBuffers& b);
  // Replaces SSBO 10 with one holding at least `pairs` face pairs.
  void grow_face_pairs(CollisionBuffers& b, std::uint32_t pairs);

  const GlSimulation& simulation_;
  std::uint64_t max_buffer_bytes_ = 0;
  bool limit_is_device_ = true;  // whether max_buffer_bytes_ is the device's, for messages
  std::array<std::uint32_t, 3> max_work_groups_{};
  std::uint32_t mask_slots_ = 0;
  std::uint32_t initial_pair_capacity_ = 0;
  ComputeProgram bb_update_;
  ComputeProgram bb_collision_;
  ComputeProgram tri_tri_octree_;
  ComputeProgram tri_tri_brute_;
  std::optional<CollisionBuffers> buffers_;
  BroadPhase last_method_ = BroadPhase::kNone;  // what download_face_pairs reruns
};

}  // namespace deformcd::gl
