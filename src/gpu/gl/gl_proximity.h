#pragma once
// Proximity candidates on the GPU (issue 12): the GLSL mirror of collision::
// emit_face_pair_candidates (shaders/proximity/proximity.glsl, with the distances of
// shaders/common/primitive_distance.glsl) over BVHs already on the GPU (a GlCollision's),
// giving exactly CpuProximity::find's list when the trees are the same.
//
// Thread-to-data mapping: proximity_refit.comp, one invocation per BVH node, writes each leaf's
// box (its face swept along its vertices' motion, grown by the face's reach) into a box buffer
// of the search's own (the collision passes' boxes are left alone); proximity_refit_level.comp,
// one dispatch per depth, deepest first, one invocation per internal node, the unions. Then one
// work item per face of each mesh pair's mesh a (items numbered pair by pair):
// proximity_count.comp: each item queries mesh b's tree with its face's swept, grown box
// (shaders/collision/bvh.glsl) and counts the candidates of every face pair it finds, into its
// own slot; proximity_scan.comp (one work group) turns the counts into offsets and the total;
// after a read-back of the total (the output is sized by it), proximity_emit.comp reruns each
// item's query and writes its candidates from its offset: in work-item order, each item's in
// its traversal order, the order CpuProximity::find returns, which no GPU schedule can change.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <vector>

#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"
#include "gpu/gl/compute_program.h"

namespace deformcd::gl {

// The search's own buffers: shaders/proximity/proximity_buffers.glsl's BINDING_PROXIMITY_*, at
// binding points the collision passes' and the contact response's private buffers also use
// (every pass binds its buffers before it dispatches).

// uint per face: its collision::primitive_owners bits
inline constexpr std::uint32_t kProximityOwnersBinding = 29;
// vec4 per vertex: its motion (xyz, m), its reach (w, m)
inline constexpr std::uint32_t kProximityMotionBinding = 30;
// uint per mesh pair + 1: its first work item
inline constexpr std::uint32_t kProximityPairFirstBinding = 31;
// uint per work item: its candidates
inline constexpr std::uint32_t kProximityCountsBinding = 32;
// uint per work item + 1: exclusive scan of the counts
inline constexpr std::uint32_t kProximityOffsetsBinding = 33;
// collision::ProximityCandidate per candidate
inline constexpr std::uint32_t kProximityCandidatesBinding = 34;
// uint per mesh: its first vertex in the motion buffer
inline constexpr std::uint32_t kProximityVertexFirstBinding = 35;
// uint per internal BVH node, deepest level first
inline constexpr std::uint32_t kProximityLevelsBinding = 36;

// The order in which the search refits its boxes over the trees it queries (bvh_work_order.h's
// refit order): GL buffer `buffer` lists the internal nodes (global indices, one uint each) by
// depth, deepest first; `levels` gives per depth (first entry, count).
struct ProximityRefitOrder {
  std::uint32_t buffer = 0;
  std::vector<glm::uvec2> levels;
};

// The buffers the search reads and does not own (GL names), laid out as a GlCollision holds
// them for the same collision::CollisionData.
struct ProximitySources {
  std::uint32_t positions = 0;  // SSBO 0: float words, found through MeshInfo::position_*
  std::uint32_t faces = 0;      // SSBO 7
  std::uint32_t meshes = 0;     // SSBO 8 (position_* set)
  std::uint32_t bvh_nodes = 0;  // SSBO 25
  std::uint32_t mesh_bvhs = 0;  // SSBO 27
  ProximityRefitOrder refit;    // of the trees in bvh_nodes
};

class GlProximity {
 public:
  // For `data`'s faces, meshes and mesh pairs (their owner bits and work items are uploaded
  // now; the trees' node counts per mesh are 2 x faces - 1, whatever their shape). Makes
  // `context` current and compiles the shaders (GlError if that fails, or when the work items
  // exceed one dispatch); the context must outlive this object and be current for every call.
  GlProximity(Context& context, const collision::CollisionData& data);
  // The same on `device` (a GlCollision's, whose context is current), from `data`'s faces,
  // meshes and mesh pairs.
  GlProximity(const DeviceInfo& device, const collision::CollisionData& data);

  // The candidates on the positions `sources` hold, as CpuProximity::find gives them: each
  // vertex moving by its `motion` (m, one per vertex of every mesh, mesh 0's first; empty:
  // none) with its `reach` (m, >= 0, one per vertex in the same order), boxes swept and grown,
  // pairs kept by their distance (emit_face_pair_candidates), over the mesh pairs
  // `mesh_pairs` (indices into the data's mesh pairs, ascending), mesh pair by mesh pair, then
  // by the querying face of the pair's first mesh, in the traversal order of the trees in
  // `sources`. Waits for the GPU (two read-backs). Throws Error for lists of the wrong length
  // or pair indices not ascending below the pair count, GlError naming the candidate buffer
  // when it would exceed the device's buffer limit or the driver refuses the memory.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find(
      const ProximitySources& sources, std::span<const float> reach,
      std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs);
  // The same over the buffers bound now at SSBOs 0, 7, 8, 25 and 27, as
  // GlCollision::prepare_proximity leaves them (a positions buffer may be bound as a range),
  // refitting in `order` (which prepare_proximity returns). Rebinds SSBO 26 and 22 and its own
  // binding points.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find_bound(
      const ProximityRefitOrder& order, std::span<const float> reach,
      std::span<const glm::vec3> motion, std::span<const std::uint32_t> mesh_pairs);

 private:
  // `vertex_first`: collision::vertex_firsts(data); `pair_first`: each mesh pair's first work
  // item, then their total. Each is made once and read twice here (a count and a buffer).
  GlProximity(const DeviceInfo& device, const collision::CollisionData& data,
              const std::vector<std::uint32_t>& vertex_first,
              const std::vector<std::uint32_t>& pair_first);
  void check_lists(std::span<const float> reach, std::span<const glm::vec3> motion,
                   std::span<const std::uint32_t> mesh_pairs) const;
  // Makes `mesh_pairs` the pairs searched (their list and work items uploaded when they
  // differ from the last search's).
  void search_pairs(std::span<const std::uint32_t> mesh_pairs);
  void set_item_uniforms();
  // Uploads the vertices' motion and reach and refits the search's boxes in `order`.
  void refit(const ProximityRefitOrder& order, std::span<const float> reach,
             std::span<const glm::vec3> motion);

  std::uint64_t max_buffer_bytes_ = 0;    // the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  std::uint32_t vertex_count_ = 0;        // of every mesh
  std::uint32_t node_count_ = 0;          // BVH nodes of every mesh
  std::vector<gpu::BodyPair> all_pairs_;  // the data's mesh pairs
  std::vector<gpu::MeshInfo> meshes_;     // the data's meshes
  std::vector<std::uint32_t> searched_;   // the pairs uploaded (indices into all_pairs_)
  std::uint32_t pair_count_ = 0;          // of them
  std::uint32_t item_count_ = 0;          // their work items (faces of their first meshes)
  ComputeProgram refit_;
  ComputeProgram refit_level_;
  ComputeProgram count_;
  ComputeProgram scan_;
  ComputeProgram emit_;
  Ssbo<std::uint32_t> owners_;                                     // per face
  Ssbo<gpu::BodyPair> mesh_pairs_;                                 // SSBO 22: searched
  Ssbo<std::uint32_t> pair_first_;                                 // per searched pair + 1
  Ssbo<std::uint32_t> vertex_first_;                               // per mesh
  Ssbo<glm::vec4> motion_;                                         // per vertex: motion, reach
  Ssbo<gpu::Box> boxes_;                                           // per BVH node (SSBO 26)
  Ssbo<std::uint32_t> counts_;                                     // per work item
  Ssbo<std::uint32_t> offsets_;                                    // per work item + 1
  std::optional<Ssbo<collision::ProximityCandidate>> candidates_;  // grown as needed
};

}  // namespace deformcd::gl
