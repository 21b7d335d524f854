#pragma once
// The line between the world and a collision backend, next to sim::SimulationBackend: the
// backend takes the static collision data once, then runs one pass per frame over the positions
// its simulation backend holds (the CPU one reads the CPU state, the GL one binds SSBO 0), and
// keeps the results on its side until asked.

#include <cstdint>
#include <string_view>
#include <vector>

#include "deformcd/collision.h"
#include "deformcd/gpu_layout.h"
#include "deformcd/world_state.h"

namespace deformcd::collision {

class CollisionBackend {
 public:
  virtual ~CollisionBackend() = default;
  CollisionBackend(const CollisionBackend&) = delete;
  CollisionBackend& operator=(const CollisionBackend&) = delete;

  /// "cpu" or "gl".
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Takes the faces, leaf-box lists and body pairs (sizes are fixed from then on). Throws
  /// Error when a buffer does not fit the device.
  virtual void upload(const WorldState& state) = 0;
  /// One pass over the current positions: resets the face flags and counters, then runs the
  /// broad phase `method` and the narrow phase (kNone only resets). Throws Error for a method
  /// the backend does not implement.
  virtual void detect(BroadPhase method) = 0;
  /// Makes sure the last pass is complete and whole: a backend whose candidate buffer
  /// overflowed grows it and reruns the pass (on the same positions). The world calls it after
  /// each pass, before the positions move again; results are read only after it.
  virtual void complete_pass() {}
  /// The last pass's counters (on GL, waits for the pass).
  [[nodiscard]] virtual gpu::CollisionCounters counters() = 0;
  /// The last pass's intersecting face pairs, in no particular order; all of them (a backend
  /// with a fixed-size result buffer grows it and reruns the pass when it overflowed).
  virtual void download_face_pairs(std::vector<gpu::FacePair>& out) = 0;
  /// The last pass's per-face flags (SSBO 5): nonzero for a face in at least one contact.
  virtual void download_face_flags(std::vector<std::uint32_t>& out) = 0;
  /// The leaf boxes as the last octree pass computed them (64 per body).
  virtual void download_boxes(std::vector<gpu::Box>& out) = 0;
  /// GL buffer name of the face flags, or 0 when the backend is not GL.
  [[nodiscard]] virtual std::uint32_t gl_face_flag_buffer() const { return 0; }

 protected:
  CollisionBackend() = default;
};

}  // namespace deformcd::collision
