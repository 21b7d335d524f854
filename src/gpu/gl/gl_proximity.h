#pragma once
// Proximity candidates on the GPU (issue 12): the GLSL mirror of collision::
// emit_face_pair_candidates (shaders/proximity/proximity.glsl) over BVHs already on the GPU (a
// GlCollision's, refitted on the current positions), giving exactly CpuProximity::find's list.
//
// Thread-to-data mapping: one work item per face of each mesh pair's mesh a (items numbered pair
// by pair). proximity_count.comp: each item queries mesh b's tree with its face's box grown by
// the two reaches (shaders/collision/bvh.glsl) and counts the candidates of every face pair it
// finds, into its own slot; proximity_scan.comp (one work group) turns the counts into offsets
// and the total; after a read-back of the total (the output is sized by it),
// proximity_emit.comp reruns each item's query and writes its candidates from its offset: in
// work-item order, each item's in its traversal order, the order CpuProximity::find returns,
// which no GPU schedule can change.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "compute_program.h"
#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"
#include "deformcd/gl/ssbo.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::gl {

// shaders/proximity/proximity_buffers.glsl's BINDING_PROXIMITY_*.
inline constexpr std::uint32_t kProximityOwnersBinding = 29;
inline constexpr std::uint32_t kProximityReachBinding = 30;
inline constexpr std::uint32_t kProximityPairFirstBinding = 31;
inline constexpr std::uint32_t kProximityCountsBinding = 32;
inline constexpr std::uint32_t kProximityOffsetsBinding = 33;
inline constexpr std::uint32_t kProximityCandidatesBinding = 34;

// The buffers the search reads and does not own (GL names), laid out as a GlCollision holds
// them for the same collision::CollisionData.
struct ProximitySources {
  std::uint32_t positions = 0;  // SSBO 0: float words, found through MeshInfo::position_*
  std::uint32_t faces = 0;      // SSBO 7
  std::uint32_t meshes = 0;     // SSBO 8 (position_* set)
  std::uint32_t bvh_nodes = 0;  // SSBO 25
  std::uint32_t bvh_boxes = 0;  // SSBO 26: refitted on the current positions
  std::uint32_t mesh_bvhs = 0;  // SSBO 27
};

class GlProximity {
 public:
  // For `data`'s faces and mesh pairs (their owner bits and work items are uploaded now).
  // Makes `context` current and compiles the three shaders (GlError if that fails, or when the
  // work items exceed one dispatch); the context must outlive this object and be current for
  // every call.
  GlProximity(Context& context, const collision::CollisionData& data);

  // The candidates on the positions `sources` hold, whose boxes swept along
  // drift[mesh_a] - drift[mesh_b] come within reach[mesh_a] + reach[mesh_b] (one reach and one
  // drift per mesh), in CpuProximity::find's order.
  // Waits for the GPU (two read-backs). Throws Error for a reach list of the wrong length,
  // GlError naming the candidate buffer when it would exceed the device's buffer limit or the
  // driver refuses the memory.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find(const ProximitySources& sources,
                                                                std::span<const float> reach,
                                                                std::span<const glm::vec3> drift);
  // The same over the buffers bound now at SSBOs 0, 7, 8, 25, 26 and 27, as
  // GlCollision::prepare_proximity leaves them (a positions buffer may be bound as a range).
  [[nodiscard]] std::vector<collision::ProximityCandidate> find_bound(
      std::span<const float> reach, std::span<const glm::vec3> drift);

 private:
  GlProximity(const DeviceInfo& device, const collision::CollisionData& data);
  void check_reach(std::span<const float> reach, std::span<const glm::vec3> drift) const;

  std::uint64_t max_buffer_bytes_ = 0;  // the device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  std::uint32_t mesh_count_ = 0;
  std::uint32_t pair_count_ = 0;
  std::uint32_t item_count_ = 0;
  ComputeProgram count_;
  ComputeProgram scan_;
  ComputeProgram emit_;
  Ssbo<std::uint32_t> owners_;                                     // per face
  Ssbo<gpu::BodyPair> mesh_pairs_;                                 // SSBO 22
  Ssbo<std::uint32_t> pair_first_;                                 // per mesh pair + 1
  Ssbo<glm::vec4> reach_;                                          // per mesh: drift, reach
  Ssbo<std::uint32_t> counts_;                                     // per work item
  Ssbo<std::uint32_t> offsets_;                                    // per work item + 1
  std::optional<Ssbo<collision::ProximityCandidate>> candidates_;  // grown as needed
};

}  // namespace deformcd::gl
