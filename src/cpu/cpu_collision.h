#pragma once
// Collision detection on the CPU, in parallel with oneTBB: the same broad phases and narrow
// phase as the GL backend's shaders (BBUpdate, BBCollision, Triangle-Triangle Intersection),
// element for element, over the positions the caller holds (read in place, one array per
// mesh). The paper's two methods (brute, octree) live here; the ones beyond it in
// cpu_octree_compact.h and cpu_bvh_broad_phase.h.

#include <cstdint>
#include <memory>
#include <vector>

#include "core/collision/collision_backend.h"
#include "cpu/cpu_bvh_broad_phase.h"
#include "cpu/cpu_narrow_phase.h"
#include "cpu/cpu_octree_compact.h"
#include "cpu/cpu_proximity.h"
#include "cpu/executor.h"

namespace deformcd::cpu {

class CpuCollision final : public collision::CollisionBackend {
 public:
  /// Runs its loops on `executor`'s threads.
  explicit CpuCollision(std::shared_ptr<Executor> executor);
  /// On an executor of its own with `threads` threads (0: every core).
  explicit CpuCollision(int threads = 0) : CpuCollision(std::make_shared<Executor>(threads)) {}

  [[nodiscard]] std::string_view name() const override { return "cpu"; }
  [[nodiscard]] std::string device() const override { return executor_->describe(); }
  void upload(const collision::CollisionData& data) override;
  /// Host sources only (Error for a GL buffer).
  void set_positions(const std::vector<collision::PositionSource>& sources) override;
  [[nodiscard]] std::vector<glm::vec3> read_positions(std::uint32_t mesh) override;
  void detect(BroadPhase method) override;
  [[nodiscard]] gpu::CollisionCounters counters() override { return counters_; }
  /// Sorted by (face_a, face_b): the same list for every method and thread count.
  void download_face_pairs(std::vector<gpu::FacePair>& out) override { out = pairs_; }
  void download_face_flags(std::vector<std::uint32_t>& out) override { out = flags_; }
  /// The leaf boxes of the last octree or octree-compact pass (a bvh pass leaves them as they
  /// were: its boxes are the BVH's, see bvh_trees()).
  void download_boxes(std::vector<gpu::Box>& out) override { out = boxes_; }

  /// Over the bvh broad phase's trees (whatever the passes' method), fitted to the query's
  /// positions first as a pass fits them (the queried trees rebuilt when degraded); the
  /// distances are always measured.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find_proximity(
      const collision::ProximityQuery& query, std::vector<float>& distances) override;
  [[nodiscard]] std::vector<collision::ProximityCandidate> widen_proximity(
      const collision::ProximityQuery& query, std::span<const std::array<std::uint32_t, 2>> widened,
      std::vector<float>& distances) override;

  /// The BVHs as the last bvh pass or proximity search fitted (and perhaps rebuilt) them.
  [[nodiscard]] const BvhTrees& bvh_trees() const { return bvh_.trees(); }

 private:
  void run(BroadPhase method);
  void update_boxes();
  // BBCollision (Algorithm 2) for one mesh pair into mask_; counts the overlapping box pairs.
  void update_box_mask(const gpu::BodyPair& pair);
  void octree_pair(const gpu::BodyPair& pair, const NarrowPhase& narrow);
  void brute_pair(const gpu::BodyPair& pair, const NarrowPhase& narrow);

  std::shared_ptr<Executor> executor_;
  std::vector<gpu::Face> faces_;
  std::vector<gpu::MeshInfo> meshes_;
  std::vector<gpu::BoxFace> box_faces_;
  std::vector<glm::uvec2> face_boxes_;
  std::vector<glm::uvec2> box_rows_;
  std::vector<gpu::BodyPair> mesh_pairs_;
  std::vector<collision::MeshVertices> vertices_;  // per mesh: the caller's array
  std::vector<std::uint32_t> vertex_counts_;       // per mesh

  std::vector<gpu::Box> boxes_;              // 64 leaf boxes per mesh
  std::vector<std::int32_t> mask_;           // one mesh pair's 64 x 64 leaf-box overlaps
  std::vector<std::uint32_t> flags_;         // per face: nonzero when it collides
  std::vector<gpu::FacePair> pairs_;         // the intersecting face pairs
  std::vector<gpu::FacePair> sort_scratch_;  // the radix sort's second buffer
  FaceGeometryCache geometry_;               // per face, this pass
  gpu::CollisionCounters counters_{};
  PairCollector collector_;
  OctreeCompactPass octree_compact_;
  BvhBroadPhase bvh_;
  std::unique_ptr<CpuProximity> proximity_;  // over bvh_'s trees; made by the first search
};

}  // namespace deformcd::cpu
