#pragma once
// The Detector's insides, for the World that composes one with its simulation (sharing the GL
// context and the CPU threads). Nothing else includes this.

#include <memory>
#include <string>
#include <vector>

#include "core/collision/collision_backend.h"
#include "core/collision/collision_data.h"
#include "cpu/executor.h"
#include "deformcd/detector.h"
#include "detector/backend_choice.h"

namespace deformcd {

struct Detector::Impl {
  /// A detector on backend `kind` (kGl or kCpu, already chosen) running in `context` (kGl) or on
  /// `executor`'s threads (kCpu). `check_positions`: whether detect() checks that positions are
  /// finite (a World checks its own state instead).
  static std::unique_ptr<Impl> create(std::vector<CollisionMesh> meshes,
                                      const DetectorOptions& options, BackendKind kind,
                                      gl::Context* context, std::shared_ptr<cpu::Executor> executor,
                                      bool check_positions);

  std::vector<CollisionMesh> meshes;
  collision::CollisionData data;
  /// Per mesh + 1: where its vertices start in find_proximity's per-vertex arrays, then their
  /// total (collision::vertex_firsts).
  std::vector<std::uint32_t> vertex_first;
  std::unique_ptr<gl::Context> owned_context;  // before the backend: destroyed after it
  gl::Context* context = nullptr;
  std::unique_ptr<collision::CollisionBackend> backend;
  std::shared_ptr<cpu::Executor> executor;  // the CPU threads
  /// The last find_proximity()'s inputs, for widen_proximity(): the positions it searched (per
  /// mesh, copied), each vertex's motion and reach (the motion's order), and the mesh pairs it
  /// searched (indices into data.mesh_pairs).
  struct ProximitySearch {
    std::vector<std::vector<glm::vec3>> pose;
    std::vector<glm::vec3> motion;
    std::vector<float> reach;
    std::vector<std::uint32_t> mesh_pairs;
    bool valid = false;
  } last_proximity;
  std::vector<collision::PositionSource> sources;
  BroadPhase broadphase = BroadPhase::kBvh;
  std::string notice;
  bool check_positions = true;
  bool prepared = false;
  bool detected = false;  // a pass ran: its results are there
  bool pending = false;   // a pass was issued and not yet completed

  void make_current() const;
  void push_sources(std::vector<collision::PositionSource> next);
  /// Throws InputError (`operation`: "mesh N does not exist ...") unless mesh `mesh` exists.
  void require_mesh(std::size_t mesh, const std::string& operation) const;
  void require_positions() const;
  void check_finite();
  void prepare();
  void complete();
  /// Where each mesh's positions are on the host now: the caller's arrays, or (GL buffers)
  /// copies read back into `read_back`.
  std::vector<collision::MeshVertices> host_vertices(
      std::vector<std::vector<glm::vec3>>& read_back);
};

}  // namespace deformcd
