#pragma once
/// \file detector.h
/// Collision detection for any triangle meshes, on their own: the caller owns the meshes and
/// their positions (a host array, or on the GL backend a buffer such as the VBO a renderer
/// draws from), moves them as it likes, and asks for the intersecting triangle pairs.
///
///     deformcd::Detector detector({{.vertex_count = n0, .triangles = t0},
///                                  {.vertex_count = n1, .triangles = t1}},
///                                 {.backend = deformcd::BackendKind::kCpu});
///     detector.set_positions(0, deformcd::HostPositions{&xyz0[0], 3 * sizeof(float)});
///     detector.set_positions(1, deformcd::HostPositions{&xyz1[0], 3 * sizeof(float)});
///     for (;;) {
///       move_my_meshes(xyz0, xyz1);  // in place: the detector reads the arrays every detect()
///       detector.detect();
///       for (const deformcd::Contact& c : detector.contacts()) { ... }
///     }
///
/// Meshes are triangle soups with indices into their own vertices: open, non-closed and
/// non-manifold surfaces are fine. A triangle whose corners are (nearly) collinear, or which
/// repeats a vertex, is degenerate: it intersects nothing (its neighbours in a surface still
/// report the contact), on both backends. The hierarchies the broad phases use (the BVH, the
/// paper's octree boxes) are built from the positions of the first detect() (or prepare()),
/// refitted every detect() and rebuilt when deformation has loosened them: never the caller's
/// business.

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/backend.h"
#include "deformcd/collision.h"
#include "deformcd/collision_mesh.h"
#include "deformcd/gpu_layout.h"

namespace deformcd {

namespace gl {
class Context;
}

/// How a Detector runs: backend, broad phase, which mesh pairs, threads.
struct DetectorOptions {
  /// KAuto: GL on a hardware device, else the CPU (backend_choice).
  BackendKind backend = BackendKind::kAuto;
  /// GL context to run in (e.g. gl::adopt_current_context() in an application that renders
  /// with OpenGL). When null, the detector creates a headless one.
  gl::Context* gl_context = nullptr;
  /// Every broad phase finds the same contacts; kBvh is the fastest by far.
  BroadPhase broadphase = BroadPhase::kBvh;
  /// The pairs of different meshes to test (e.g. leave out two glued meshes). When empty, every
  /// pair of different meshes; a mesh is tested with itself when its self_collision is set or
  /// the list names (m, m).
  std::optional<std::vector<MeshPair>> mesh_pairs = std::nullopt;
  /// CPU threads; 0 uses every core. Results do not depend on it.
  int threads = 0;
};

/// Positions in host memory: vertex i's x, y, z are the floats at
/// `data + i * stride_bytes` (e.g. 12 for packed xyz, 16 for vec4). The array stays the
/// caller's: it is read in place by every detect() and must outlive the detector or the next
/// set_positions() of the mesh.
struct HostPositions {
  const float* data = nullptr;                   ///< x of vertex 0; must not be null
  std::size_t stride_bytes = 3 * sizeof(float);  ///< bytes from one vertex to the next (>= 12)
};

/// Positions in a GL buffer the caller owns (GL backend only): vertex i's x, y, z are the floats
/// at byte `offset_bytes + i * stride_bytes` of buffer `buffer` (both multiples of 4). The
/// shaders read the buffer where it is when every GL-positioned mesh uses the same buffer;
/// meshes spread over several buffers are first copied, on the GPU, into one of the
/// detector's. The buffer must stay alive, and must not be written between a detect() and the
/// reading of its results (or complete()).
struct GlPositions {
  std::uint32_t buffer = 0;      ///< GL buffer name (not 0)
  std::size_t offset_bytes = 0;  ///< byte offset of vertex 0 (a multiple of 4)
  /// Bytes from one vertex to the next (a multiple of 4, >= 12).
  std::size_t stride_bytes = 4 * sizeof(float);
};

/// A vertex near a triangle, or an edge near an edge (see Detector::find_proximity).
struct ProximityPair {
  /// What the two primitives are.
  enum class Kind : std::uint8_t {
    kVertexTriangle,  ///< a vertex of mesh_a and a triangle of mesh_b
    kEdgeEdge,        ///< an edge of mesh_a and an edge of mesh_b
  };
  Kind kind = Kind::kVertexTriangle;  ///< what the two primitives are
  std::uint32_t mesh_a = 0;  ///< the mesh of the vertex (kVertexTriangle) or of the first edge
  std::uint32_t mesh_b = 0;  ///< the mesh of the triangle or of the second edge
  /// kVertexTriangle: the vertex of mesh_a, then the three vertices of mesh_b's triangle
  /// `triangle`; kEdgeEdge: an edge of mesh_a (two vertices), then an edge of mesh_b.
  std::array<std::uint32_t, 4> vertices = {};
  std::uint32_t triangle = 0;  ///< kVertexTriangle: the triangle's index in mesh_b; else 0
  float distance = 0.0f;       ///< m, between the two primitives on the current positions

  /// Every field equal.
  friend bool operator==(const ProximityPair&, const ProximityPair&) = default;
};

/// Which of a detector's mesh pairs a proximity search looks at (Detector::find_proximity);
/// by default every pair detect() tests.
struct ProximityPairs {
  /// The pairs of two different meshes.
  bool between = true;
  /// Per mesh (or empty: every mesh), whether its pairs with itself are searched (for a mesh
  /// with self-collision): a response that holds some bodies' self-contact pairs from a search
  /// of their own leaves them out.
  std::span<const std::uint8_t> within = {};
};

/// Collision detection between triangle meshes whose positions the caller owns (host arrays
/// or GL buffers), on the GL or the CPU backend, with the same contacts on both: see
/// docs/detector.md. Move-only; calls on one detector must not overlap.
class Detector {
 public:
  /// Checks the meshes (every index below vertex_count; at least one triangle each), the mesh
  /// pairs and the options, and creates the backend. Throws InputError naming the mesh and the
  /// triangle or pair, GlError for kGl without OpenGL 4.3.
  explicit Detector(std::vector<CollisionMesh> meshes, const DetectorOptions& options = {});
  ~Detector();
  Detector(Detector&&) noexcept;  ///< the moved-from detector may only be destroyed or assigned
  Detector& operator=(
      Detector&&) noexcept;  ///< the moved-from detector may only be destroyed or assigned
  Detector(const Detector&) = delete;
  Detector& operator=(const Detector&) = delete;

  [[nodiscard]] std::size_t mesh_count() const;  ///< the meshes given to the constructor
  [[nodiscard]] const CollisionMesh& mesh(
      std::size_t mesh) const;  ///< mesh `mesh` as given to the constructor
  /// Where mesh `mesh`'s triangles start in face_flags() and in the GL buffers.
  [[nodiscard]] std::uint32_t face_offset(std::size_t mesh) const;
  /// Triangles of every mesh.
  [[nodiscard]] std::size_t face_count() const;

  /// Where mesh `mesh`'s positions are read from, from the next detect() on. Throws
  /// InputError for a mesh that does not exist, a null array or a stride below 12 bytes, and
  /// for GL positions: Error on the CPU backend, InputError for buffer 0, an offset or stride
  /// not a multiple of 4, or a buffer smaller than offset + stride x (vertex_count - 1) + 12.
  /// The detector is unchanged when it throws.
  void set_positions(std::size_t mesh, const HostPositions& positions);
  /// The same for positions in a GL buffer (GL backend only).
  void set_positions(std::size_t mesh, const GlPositions& positions);
  /// The same as HostPositions{&v[0].x, sizeof(glm::vec3)}; `v` must hold vertex_count
  /// positions (InputError otherwise) and stay where it is.
  void set_positions(std::size_t mesh, std::span<const glm::vec3> v);

  /// The broad phase detect() runs; every one finds the same contacts.
  [[nodiscard]] BroadPhase broadphase() const;
  void set_broadphase(BroadPhase method);  ///< takes effect at the next detect()

  /// Builds the hierarchies from the current positions now (otherwise the first detect() does).
  void prepare();
  /// One pass over the current positions. Throws InputError when a mesh has no positions set,
  /// or (then the last results stay) when a position is NaN or infinite, naming the mesh and
  /// the vertex; on GL, positions in a buffer are checked on the GPU. On GL the pass is queued:
  /// the results' getters (or complete()) wait for it.
  void detect();
  /// Waits for the last pass; a GL pass whose lists overflowed is grown and rerun on the same
  /// positions. Call it before overwriting positions held in a GL buffer. Cheap when complete.
  void complete();

  /// The intersecting triangle pairs of the last pass, sorted by (a.body, a.face, b.body,
  /// b.face), a.body <= b.body (body = mesh index, face = triangle index in the caller's
  /// order, nodes = its vertex indices); the same on every backend and broad phase.
  [[nodiscard]] std::vector<Contact> contacts() const;
  /// The vertex-triangle and edge-edge pairs that may come closer than the sum of their
  /// reaches over a period in which each vertex moves by its `motion` (m; one per vertex of
  /// every mesh, mesh 0's first, in vertex order; empty: none) and strays at most its reach from
  /// that straight path. `reach` (m, >= 0) is one per mesh, or one per vertex of every mesh
  /// (in the motion's order); a primitive's reach is the largest of its vertices'. The pairs
  /// are those whose boxes, swept along the motion and grown by their reaches, overlap on the
  /// current positions, and whose distance now, less the most their vertices' relative motion
  /// can close of it, is within the sum of the reaches (a superset of the pairs that come
  /// closer than the sum). Over the mesh pairs detect() tests; within one mesh, a vertex and a
  /// triangle it is a corner of, or two edges sharing a vertex, are neighbours and left out
  /// (other primitives of triangles sharing a vertex are pairs). Each pair once, in a fixed order
  /// (mesh pair by mesh pair, then by the triangle of the pair's first mesh whose search found
  /// it, in the traversal order of the other mesh's hierarchy), the same on every thread count.
  /// Both backends find the same pairs with the same distances, in the same order while their
  /// hierarchies are the same (built on the same positions; each backend rebuilds a hierarchy
  /// that deformation has loosened on its own schedule). For a contact response that keeps
  /// bodies `thickness` apart: reach = thickness / 2 + the most a vertex strays from its path.
  /// `still` (one flag per mesh, or none) names meshes that do not move over the period (a
  /// fixed base, a sleeping body): the pairs between two of them, and a still mesh's pairs
  /// with itself, are not searched for (the rest are the same pairs in the same order), since
  /// no response could move them apart. `pairs` narrows the mesh pairs further (the pairs
  /// between meshes, or some meshes' with themselves, left out). Throws InputError for lists of
  /// the wrong length, a negative or non-finite reach or a non-finite motion.
  [[nodiscard]] std::vector<ProximityPair> find_proximity(std::span<const float> reach,
                                                          std::span<const glm::vec3> motion = {},
                                                          std::span<const std::uint8_t> still = {},
                                                          const ProximityPairs& pairs = {});
  /// Raises the reach of some vertices in the last find_proximity() (`vertices` numbered as
  /// its motion, mesh 0's first; `reach` one per vertex named, m, >= 0) and returns the pairs
  /// that involve one of them: exactly the pairs involving them that find_proximity() would
  /// return with those reaches, on the positions, motions, still meshes and mesh pairs it was
  /// given (kept from then: the meshes may have moved since), in an order of its own (by the
  /// pair's triangles). The other pairs of the last search stand as they were. For a contact
  /// response whose vertex strayed beyond its reach: only the triangles at those vertices query the
  /// hierarchies, instead of a new search over every triangle. The reaches stay raised for the next
  /// call. On either backend the work is the CPU's (a few triangles). Throws Error before a
  /// find_proximity(), InputError for a vertex out of range or a negative or non-finite reach.
  [[nodiscard]] std::vector<ProximityPair> widen_proximity(std::span<const std::uint32_t> vertices,
                                                           std::span<const float> reach);
  /// Counts of the last pass (all 0 before the first).
  [[nodiscard]] CollisionCounts counts() const;
  /// One flag per triangle of every mesh (mesh m's from face_offset(m)): 1 when the triangle is
  /// in a contact of the last pass, else 0.
  [[nodiscard]] std::vector<std::uint32_t> face_flags() const;
  /// The 64 octree leaf boxes per mesh as the last octree pass computed them (mesh m's at 64 m).
  [[nodiscard]] std::vector<gpu::Box> leaf_boxes() const;

  /// GL backend: the buffer of face flags (one uint per triangle, as face_flags()), ready for a
  /// shader once the last pass is complete; 0 on the CPU.
  [[nodiscard]] std::uint32_t gl_face_flag_buffer() const;
  /// GL backend: the buffer of the last pass's intersecting pairs as gpu::FacePair records
  /// (face indices over every mesh, i.e. face_offset(m) + triangle; in no particular order),
  /// the first counts().contacts of them valid; 0 on the CPU.
  [[nodiscard]] std::uint32_t gl_contact_buffer() const;

  /// "gl" or "cpu".
  [[nodiscard]] std::string_view backend_name() const;
  /// The GL renderer and version, or the CPU thread count.
  [[nodiscard]] std::string device() const;
  /// Why kAuto chose the CPU, if it did; else empty.
  [[nodiscard]] const std::string& notice() const;

  struct Impl;

 private:
  explicit Detector(std::unique_ptr<Impl> impl);
  friend class World;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deformcd
