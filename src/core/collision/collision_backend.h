#pragma once
// The line between a Detector and a collision backend (src/cpu: CpuCollision, src/gpu/gl:
// GlCollision): the backend takes the collision data once (faces, mesh pairs, hierarchies),
// is told where each mesh's positions are, then runs one pass per detect() and keeps the results
// on its side until asked. Its second phase, the proximity search, runs over the same trees
// (one per mesh). The Detector checks every input before it reaches a backend.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "deformcd/collision.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Where one mesh's positions are: a host array or (GL backend) a GL buffer.
struct PositionSource {
  enum class Kind { kNone, kHost, kGl };
  Kind kind = Kind::kNone;
  const float* host = nullptr;     ///< kHost
  std::uint32_t gl_buffer = 0;     ///< kGl
  std::uint64_t offset_bytes = 0;  ///< kGl
  std::uint64_t stride_bytes = 0;  ///< both
  std::uint32_t vertex_count = 0;  ///< the mesh's (read_positions may be called before upload)
};

/// A proximity search's inputs, checked: each vertex's position where the period starts, its
/// motion over the period and its reach, per mesh (host arrays) and, motion and reach, also flat
/// over every mesh's vertices (mesh 0's first: collision::vertex_firsts), and the mesh pairs
/// searched.
struct ProximityQuery {
  VertexPositions positions = nullptr;        ///< per mesh, on the host
  VertexPositions motion = nullptr;           ///< per mesh (m), or null: none
  VertexReach reach = nullptr;                ///< per mesh, per vertex (m, >= 0)
  std::span<const glm::vec3> flat_motion;     ///< the motions, flat; empty: none
  std::span<const float> flat_reach;          ///< the reaches, flat
  std::span<const std::uint32_t> mesh_pairs;  ///< indices into the data's pairs, ascending
};

class CollisionBackend {
 public:
  virtual ~CollisionBackend() = default;
  CollisionBackend(const CollisionBackend&) = delete;
  CollisionBackend& operator=(const CollisionBackend&) = delete;

  /// "cpu" or "gl".
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// The GL renderer and version, or the CPU thread count.
  [[nodiscard]] virtual std::string device() const = 0;
  /// Takes the collision data with its hierarchies built (sizes are fixed from then on). Throws
  /// Error when a buffer does not fit the device; the backend is unchanged then.
  virtual void upload(const CollisionData& data) = 0;
  /// Where each mesh's positions are read from (one source per mesh, checked by the Detector),
  /// from the next detect() on. The CPU backend takes kHost sources only.
  virtual void set_positions(const std::vector<PositionSource>& sources) = 0;
  /// The current positions of mesh `mesh` (read back from a GL buffer), for building and
  /// rebuilding hierarchies and for error messages. Valid after set_positions, before upload.
  [[nodiscard]] virtual std::vector<glm::vec3> read_positions(std::uint32_t mesh) = 0;
  /// The first vertex with a non-finite coordinate, as (mesh, vertex), or nothing. Sources in
  /// host memory are the Detector's to check; a GL backend checks its GL buffers (on the GPU).
  [[nodiscard]] virtual bool find_non_finite(std::uint32_t& mesh, std::uint32_t& vertex) {
    (void)mesh;
    (void)vertex;
    return false;
  }
  /// One pass over the current positions: resets the face flags and counters, then runs the
  /// broad phase `method` and the narrow phase (kNone only resets).
  virtual void detect(BroadPhase method) = 0;
  /// Makes sure the last pass is complete and whole: a backend whose lists overflowed grows
  /// them and reruns the pass (on the same positions). Results are read only after it.
  virtual void complete_pass() {}
  /// The last pass's counters.
  [[nodiscard]] virtual gpu::CollisionCounters counters() = 0;
  /// The last pass's intersecting face pairs (face indices over every mesh, face_a < face_b),
  /// in no particular order.
  virtual void download_face_pairs(std::vector<gpu::FacePair>& out) = 0;
  /// The last pass's per-face flags: nonzero for a face in at least one contact.
  virtual void download_face_flags(std::vector<std::uint32_t>& out) = 0;
  /// The leaf boxes as the last octree pass computed them (64 per mesh).
  virtual void download_boxes(std::vector<gpu::Box>& out) = 0;
  /// The proximity phase over the backend's trees (kept fitted by their upkeep rule), on the
  /// query's positions (the CPU) or on the backend's sources staged as a pass stages them
  /// (GL: the same positions, which the query's are read from): every vertex-face and
  /// edge-edge pair whose boxes, swept along the motion and grown by the reaches, meet and
  /// whose primitives come within the two reaches (collision::emit_face_pair_candidates),
  /// mesh pair by mesh pair, then by the querying face of the pair's first mesh (in traversal
  /// order within a face). `distances`: each candidate's primitives' distance on the query's
  /// positions, in the same order, or empty when the caller is to measure them (GL). The last
  /// pass's results stay as they are.
  [[nodiscard]] virtual std::vector<ProximityCandidate> find_proximity(
      const ProximityQuery& query, std::vector<float>& distances) = 0;
  /// After a find_proximity() over the same positions, motion and mesh pairs, the reaches of
  /// the vertices `widened` (mesh, vertex) raised since (in query.reach): the candidates
  /// find_proximity() would now give that involve one of them, with their distances, ordered
  /// by face pair whatever the trees and threads (cpu::CpuProximity::widen, on the host).
  [[nodiscard]] virtual std::vector<ProximityCandidate> widen_proximity(
      const ProximityQuery& query, std::span<const std::array<std::uint32_t, 2>> widened,
      std::vector<float>& distances) = 0;
  /// GL buffer names of the face flags and of the face pairs, or 0 when the backend is not GL.
  [[nodiscard]] virtual std::uint32_t gl_face_flag_buffer() const { return 0; }
  [[nodiscard]] virtual std::uint32_t gl_face_pair_buffer() const { return 0; }

 protected:
  CollisionBackend() = default;
};

}  // namespace deformcd::collision
