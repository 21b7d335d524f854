#pragma once
// Collision detection on the CPU, in parallel with oneTBB: the same broad phases and narrow
// phase as the GL backend's shaders (BBUpdate, BBCollision, Triangle-Triangle Intersection),
// element for element, over the positions the CPU simulation holds.

#include <cstdint>
#include <vector>

#include "core/collision/collision_backend.h"
#include "cpu_simulation.h"

namespace deformcd::cpu {

class CpuCollision final : public collision::CollisionBackend {
 public:
  /// Reads node positions from `simulation`, which must outlive this object.
  explicit CpuCollision(const CpuSimulation& simulation) : simulation_(simulation) {}

  [[nodiscard]] std::string_view name() const override { return "cpu"; }
  void upload(const WorldState& state) override;
  void detect(BroadPhase method) override;
  [[nodiscard]] gpu::CollisionCounters counters() override { return counters_; }
  void download_face_pairs(std::vector<gpu::FacePair>& out) override { out = pairs_; }
  void download_face_flags(std::vector<std::uint32_t>& out) override { out = flags_; }
  void download_boxes(std::vector<gpu::Box>& out) override { out = boxes_; }

 private:
  void update_boxes();
  void octree_pair(const gpu::BodyPair& pair);
  void brute_pair(const gpu::BodyPair& pair);
  // The exact test of one face pair; records it when the faces intersect.
  void test_faces(std::uint32_t face_a, std::uint32_t face_b, std::vector<gpu::FacePair>& out);
  void collect(std::vector<std::vector<gpu::FacePair>>& per_row);

  const CpuSimulation& simulation_;
  std::vector<gpu::Face> faces_;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<gpu::BoxFace> box_faces_;
  std::vector<glm::uvec2> face_boxes_;
  std::vector<glm::uvec2> box_rows_;
  std::vector<gpu::BodyPair> body_pairs_;

  std::vector<gpu::Box> boxes_;       // SSBO 4
  std::vector<std::int32_t> mask_;    // SSBO 11, one body pair's 64 x 64
  std::vector<std::uint32_t> flags_;  // SSBO 5
  std::vector<gpu::FacePair> pairs_;  // SSBO 10
  gpu::CollisionCounters counters_{};
};

}  // namespace deformcd::cpu
