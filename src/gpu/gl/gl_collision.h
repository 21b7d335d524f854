#pragma once
// Collision detection on the GPU: the paper's compute shaders 0 (BBUpdate), 1 (BBCollision) and
// 2 (Triangle-Triangle Intersection), the paper's all-pairs baseline, and two broad phases
// beyond the paper (octree-compact, bvh), over a detector's meshes (collision::CollisionData):
// every mesh pair it lists, a pair (m, m) testing mesh m with itself. Same pairs as the CPU
// backend (src/cpu/cpu_collision.*), which runs the same algorithms on the same floats.
//
// Positions are the caller's (set_positions): read in place when every mesh's are in one GL
// buffer (a World: the simulation's SSBO 0), else gathered each pass into one buffer of ours
// (gl_position_staging.h); the shaders find mesh m's vertex i at MeshInfo m's word offset + i x
// its word stride (shaders/collision/surface.glsl).
//
// One pass (detect):
//   stage    the GL sources checked (still there, large enough), positions gathered if need be;
//   reset    face flags (SSBO 5) and counters (SSBO 23) cleared with glClearBufferData;
//   octree   bb_update.comp: one invocation per leaf box of every mesh (64 x meshes, work
//            groups of 4 as in the paper) recomputes the box from its faces' vertices; then for
//            each chunk of at most mask_slots mesh pairs, bb_collision.comp (64 x 64 x chunk)
//            fills one 64 x 64 mask slot per pair, and tri_tri_octree.comp (N' x M' x chunk, the
//            chunk's largest row counts) tests the row pairs whose boxes overlap, each face pair
//            from the first overlapping box pair listing both faces only;
//   brute    tri_tri_brute.comp (N x M x chunk) tests every face pair;
//   octree-compact  bb_update.comp as the octree; bb_pair_list.comp (64 x 64 x chunk) appends
//            the overlapping leaf-box pairs to a list; octree_candidates.comp (indirect: one work
//            group per listed box pair) appends the face pairs the octree would test, and
//            tri_tri_candidates.comp (indirect) tests those only;
//   bvh      bvh_refit.comp refits every mesh's BVH leaves, bvh_refit_level.comp the internal
//            nodes level by level, deepest first;
//            bvh_mesh_pairs.comp lists the mesh pairs whose root boxes overlap; bvh_traverse.comp
//            (indirect: the smaller mesh's leaves x listed pairs) queries the other mesh's
//            tree with each leaf's box and appends the overlapping face pairs;
//            tri_tri_candidates.comp (indirect) tests those only.
// The indirect dispatches take their sizes from dispatch_args.comp, which reads the counts on
// the GPU: nothing is read back inside a pass. Intersecting pairs go to SSBO 10, candidates to
// SSBO 28 and listed box pairs to private SSBO 30, at slots taken with atomicAdd; what overflows
// is counted, not written. complete_pass() reads the counters at the frame boundary and, when a
// list overflowed, grows it and reruns the pass on the same positions (the staged ones), so
// every result read is whole. Every bvh_check_interval completed bvh passes it also reads the
// refitted boxes back and rebuilds on the host the trees that deformation has degraded
// (collision::BvhUpkeep, the policy the CPU backend follows too).

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_backend.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "gpu/gl/bvh_work_order.h"
#include "gpu/gl/collision_buffers.h"
#include "gpu/gl/collision_upload_checks.h"
#include "gpu/gl/compute_program.h"
#include "gpu/gl/gl_position_staging.h"
#include "gpu/gl/gl_proximity.h"
#include "gpu/gl/gl_vertex_check.h"

namespace deformcd::cpu {
class CpuProximity;
class Executor;
}  // namespace deformcd::cpu

namespace deformcd::gl {

struct GlCollisionOptions {
  // Largest buffer upload() accepts, in bytes (the gathered positions too). 0: the device's
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  std::uint64_t max_buffer_bytes = 0;
  // Mesh pairs per octree chunk, each taking one 64 x 64 int mask slot (16 KiB): the mask's
  // memory is min(mask_slots, mesh pairs) x 16 KiB, whatever the number of meshes. Must be
  // positive; capped at the device's z work-group count.
  std::uint32_t mask_slots = 64;
  // Face-pair slots (SSBO 10, 48 bytes each) allocated by upload(). 0: max(1024, 4 x faces),
  // capped at what the buffer limit allows. The buffer grows (x 1.5 the count) when a pass finds
  // more pairs.
  std::uint32_t initial_pair_capacity = 0;
  // Candidate face pairs (SSBO 28, 8 bytes each) of the bvh and octree-compact broad phases. 0:
  // max(4096, 16 x faces), capped at what the buffer limit allows. Grows (x 1.5 the count) when
  // a pass appends more.
  std::uint32_t initial_candidate_capacity = 0;
  // Entries of octree-compact's list of overlapping leaf-box pairs (8 bytes each). 0: 4096 per
  // mesh pair, at most 4096 x meshes. Grows (x 1.5 the count) when a pass finds more.
  std::uint32_t initial_box_pair_capacity = 0;
  // Completed bvh passes between two checks of the trees' quality (a read-back of the BVH
  // boxes). Must be positive.
  std::uint32_t bvh_check_interval = 30;
};

class GlCollision final : public collision::CollisionBackend {
 public:
  // Makes `context` current and compiles the shaders (GlError if that fails). The context must
  // outlive this object and be current on the calling thread for every call, destruction
  // included. Throws Error when options.mask_slots or options.bvh_check_interval is 0.
  // `executor`: the host threads a widened proximity search runs on (null: every core, made
  // when first needed).
  explicit GlCollision(Context& context, const GlCollisionOptions& options = {},
                       std::shared_ptr<cpu::Executor> executor = nullptr);
  ~GlCollision() override;
  GlCollision(const GlCollision&) = delete;
  GlCollision& operator=(const GlCollision&) = delete;

  [[nodiscard]] std::string_view name() const override { return "gl"; }
  // Renderer, GL version and EGL platform.
  [[nodiscard]] std::string device() const override { return device_; }
  // Checks the collision data, hierarchies built (Error when inconsistent), the buffer sizes
  // (GlError naming every buffer over the limit, with its size and the limit) and the dispatch
  // sizes (GlError naming the shader) before allocating anything, then replaces the buffers;
  // the previous ones are kept when it throws. Flags and counters start at 0, the boxes empty.
  // The BVHs' reference quality is measured on the current positions when every mesh has some
  // (the ones the hierarchies were built on), else at the next detect().
  void upload(const collision::CollisionData& data) override;
  // Where each mesh's positions are (kNone: not set yet), from the next detect() on. Checks
  // each source (a GL buffer must exist and hold the mesh's vertex_count vertices) and throws
  // Error naming the mesh and the buffer otherwise, unchanged then. kGl sources all naming one
  // buffer are read in place.
  void set_positions(const std::vector<collision::PositionSource>& sources) override;
  // Mesh `mesh`'s current positions: read from its host array, or back from its GL buffer
  // (waits for the GPU). Needs set_positions only. Throws Error for a mesh without positions.
  [[nodiscard]] std::vector<glm::vec3> read_positions(std::uint32_t mesh) override;
  // The lowest (mesh, vertex) with a NaN or infinite coordinate among the meshes whose
  // positions are in GL buffers (gl_vertex_check.h; host arrays are the Detector's to check).
  // Needs set_positions only; one read-back; the last pass's results stay as they are.
  [[nodiscard]] bool find_non_finite(std::uint32_t& mesh, std::uint32_t& vertex) override;
  // One pass over the current positions, queued without waiting for it: stages the positions
  // (a host array's are copied now), resets the outputs and runs the broad phase. kNone only
  // resets the flags and counters. Throws Error before upload(), and (then nothing ran and the
  // last results stay) for a mesh without positions or whose GL buffer no longer holds them.
  void detect(BroadPhase method) override;
  // Waits for the last pass; if a list overflowed, grows it and reruns the pass on the staged
  // positions (at most 3 times: a pass is deterministic in what it counts); after a bvh pass,
  // maybe rebuilds trees. Does nothing when the last pass is already complete. Throws Error when
  // reruns do not settle (a caller's buffer read in place changed), GlError when a list cannot
  // grow within the buffer limit or the driver refuses the memory (naming the list and its
  // size). Then the pass is lost: it overwrote the previous results and its own lists are
  // partial. The buffers stay as they were and the next detect() runs normally; until then
  // the reads below throw the same kind of error, saying why.
  void complete_pass() override;
  // The reads complete the pass first.
  [[nodiscard]] gpu::CollisionCounters counters() override;
  void download_face_pairs(std::vector<gpu::FacePair>& out) override;
  void download_face_flags(std::vector<std::uint32_t>& out) override;
  void download_boxes(std::vector<gpu::Box>& out) override;
  // On the GPU (gl_proximity.h, made by the first search) over this backend's trees and
  // positions, staged as a pass stages them: completes the last pass first (its results stay).
  // Waits for the GPU; leaves `distances` empty (the caller measures them on the host).
  [[nodiscard]] std::vector<collision::ProximityCandidate> find_proximity(
      const collision::ProximityQuery& query, std::vector<float>& distances) override;
  // On the host (cpu::CpuProximity), over the host copy of this backend's trees.
  [[nodiscard]] std::vector<collision::ProximityCandidate> widen_proximity(
      const collision::ProximityQuery& query, std::span<const std::array<std::uint32_t, 2>> widened,
      std::vector<float>& distances) override;
  // SSBO 5 and SSBO 10 (0 before upload()).
  [[nodiscard]] std::uint32_t gl_face_flag_buffer() const override;
  [[nodiscard]] std::uint32_t gl_face_pair_buffer() const override;

  // The BVH boxes (one per node, global indices) as the last bvh pass refitted them.
  void download_bvh_boxes(std::vector<gpu::Box>& out);
  // The BVH nodes as the GPU holds them (rebuilds replace a mesh's).
  void download_bvh_nodes(std::vector<gpu::BvhNode>& out);
  // The meshes as the shaders read them (SSBO 8: position_* as the last detect() staged them).
  void download_meshes(std::vector<gpu::MeshInfo>& out);
  // Slots in SSBO 10 (face pairs), 28 (candidates) and the box-pair list now (0 before upload()).
  [[nodiscard]] std::uint32_t face_pair_capacity() const;
  [[nodiscard]] std::uint32_t candidate_capacity() const;
  [[nodiscard]] std::uint32_t box_pair_capacity() const;
  // Trees rebuilt since upload() (0 before).
  [[nodiscard]] std::uint64_t bvh_rebuilds() const { return upkeep_.rebuilds(); }
  // Whether the last detect() read the caller's buffer in place (no gathering copy).
  [[nodiscard]] bool positions_in_place() const;

 private:
  GlCollision(const DeviceInfo& device, const GlCollisionOptions& options,
              std::shared_ptr<cpu::Executor> executor);
  // For a proximity search (gl_proximity.h) on the current positions: completes the last pass,
  // stages the positions and leaves bound what GlProximity::find_bound reads (SSBOs 0, 7, 8,
  // 25, 27); returns the trees' refit order for the search's own boxes. The last pass's results
  // and boxes stay as they are. Throws as detect() does (gl_collision_proximity.cpp).
  [[nodiscard]] ProximityRefitOrder prepare_proximity();
  CollisionBuffers& buffers(const char* operation);
  [[nodiscard]] std::string limit_name() const;
  [[nodiscard]] CollisionCapacities initial_capacities(const collision::CollisionData& data) const;
  // Throws GlError naming the first shader whose dispatch would exceed the device's limits.
  void check_dispatches(const CollisionBuffers& b) const;
  void set_capacity_uniforms(const CollisionBuffers& b);
  // Stages the positions and re-uploads the meshes' position words when they changed.
  void stage_positions(CollisionBuffers& b);
  // Binds everything, resets the outputs and runs `method` on the staged positions.
  void run_pass(BroadPhase method, const CollisionBuffers& b);
  // The passes (gl_collision_passes.cpp); run_pass has bound the buffers and reset the outputs.
  void run(BroadPhase method, const CollisionBuffers& b);
  void run_octree(const CollisionBuffers& b);
  void run_brute(const CollisionBuffers& b);
  void run_octree_compact(const CollisionBuffers& b);
  void run_bvh(const CollisionBuffers& b);
  // bvh_refit.comp and bvh_refit_level.comp, deepest level first (no barrier after the last).
  void refit_bvhs(const CollisionBuffers& b);
  // dispatch_args.comp, then tri_tri_candidates.comp over the candidates, indirectly.
  void run_candidate_narrow_phase(const CollisionBuffers& b);
  // A list an indirect dispatch covers (dispatch_args.comp's uniforms).
  struct IndirectList {
    std::uint32_t source = 0;    // 0: counters.box_pairs, 1: counters.candidates, 2: touching pairs
    std::uint32_t capacity = 0;  // entries stored
    std::uint32_t count_axis = 0;    // 0: the list runs along x, 1: along y
    std::uint32_t other_groups = 1;  // work groups along the other axis
  };
  // Writes the indirect arguments covering min(count, capacity) entries of `list` with work
  // groups of `local_size` along its axis, at uint `word` of the dispatch-args buffer.
  void write_dispatch_args(const IndirectList& list, std::uint32_t local_size, std::uint32_t word);
  // Throws when the last pass was lost (complete_pass).
  void require_results(const char* operation) const;
  // Whether the last pass's counts `found` exceed a list's capacity (gl_collision_completion.cpp).
  [[nodiscard]] bool overflowed(const CollisionBuffers& b,
                                const gpu::CollisionCounters& found) const;
  // Replaces each list that `found` overflowed by one 1.5 x the count (GlError past the limit
  // or when the driver refuses one; then no list is replaced).
  void grow_overflowed(CollisionBuffers& b, const gpu::CollisionCounters& found);
  // Whether every mesh of `meshes` has positions of its vertex count.
  [[nodiscard]] bool positions_cover(const std::vector<gpu::MeshInfo>& meshes) const;
  // The BVHs of `data` with their reference quality measured on every mesh's current positions
  // (the ones they were built on).
  [[nodiscard]] collision::BvhUpkeep measured_bvh_upkeep(
      const collision::CollisionData& data) const;
  // Every bvh_check_interval completed bvh passes: rebuilds the degraded trees.
  void maintain_bvhs(CollisionBuffers& b);
  // The largest element count of a buffer of `element_bytes` under the limit.
  [[nodiscard]] std::uint64_t most_elements(std::uint64_t element_bytes) const;

  DeviceInfo device_info_;
  std::string device_;
  std::uint64_t max_buffer_bytes_ = 0;
  bool limit_is_device_ = true;  // whether max_buffer_bytes_ is the device's, for messages
  std::array<std::uint32_t, 3> max_work_groups_{};
  std::uint32_t mask_slots_ = 0;
  std::uint32_t initial_pair_capacity_ = 0;
  std::uint32_t initial_candidate_capacity_ = 0;
  std::uint32_t initial_box_pair_capacity_ = 0;
  std::uint32_t bvh_check_interval_ = 1;
  ComputeProgram bb_update_;
  ComputeProgram bb_collision_;
  ComputeProgram tri_tri_octree_;
  ComputeProgram tri_tri_brute_;
  ComputeProgram bb_pair_list_;
  ComputeProgram octree_candidates_;
  ComputeProgram bvh_refit_;
  ComputeProgram bvh_refit_level_;
  ComputeProgram bvh_mesh_pairs_;
  ComputeProgram bvh_traverse_;
  ComputeProgram dispatch_args_;
  ComputeProgram tri_tri_candidates_;
  VertexCheck vertex_check_;
  PositionStaging staging_;
  std::vector<gpu::MeshInfo> meshes_;        // as SSBO 8 holds them
  std::optional<CollisionBuffers> buffers_;  // after upload()
  collision::BvhUpkeep upkeep_;
  std::optional<collision::CollisionData> upkeep_pending_;  // reset at the next detect()
  std::vector<gpu::BodyPair> mesh_pairs_;                   // the data's
  std::shared_ptr<cpu::Executor> executor_;                 // for widen_proximity
  std::unique_ptr<GlProximity> proximity_;                  // made by the first search
  std::unique_ptr<cpu::CpuProximity> host_proximity_;       // made by the first widening
  std::uint32_t bvh_passes_ = 0;                // completed bvh passes since the last check
  BroadPhase last_method_ = BroadPhase::kNone;  // what complete_pass reruns
  bool pass_pending_ = false;                   // detect() ran, complete_pass() did not since
  struct LostPass {
    std::string why;  // the error complete_pass threw
    bool gl = false;  // whether it was a GlError
  };
  std::optional<LostPass> lost_pass_;  // the last pass could not complete; reset by detect()
};

}  // namespace deformcd::gl
