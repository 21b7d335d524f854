#pragma once
// Proximity candidates on the host (issue 12): for each mesh pair searched, the vertex-face and
// edge-edge pairs whose swept boxes come within the two meshes' reaches, found over the trees a
// collision backend already holds (collision::BvhUpkeep: one tree per mesh for the intersection
// passes and this search), with boxes of its own: each leaf its face swept along its vertices'
// motion and grown by its reach, each parent the union of its children. The owner keeps the
// trees fitted (rebuilds them by the shared upkeep rule); the search only reads their topology.
// Each mesh pair's two trees are descended together (cpu_bvh_pair_traversal.h, over records of
// this search's boxes), a tree against itself visiting each pair of its leaves once instead of
// once from each face; the face pairs met are then put in the order of one query per face of the
// pair's first mesh (by that face, then by the other's leaf, which a depth-first query meets in
// preorder), and their candidates are emitted in fixed chunks of that list, joined in order: the
// result does not depend on the thread count and is the GL search's order over the same trees. A
// search can then be widened (widen()): some vertices' reaches raised, only the faces at them swept
// again and queried.
//
// The CPU backend runs every search here (CpuCollision::find_proximity); the GL backend runs
// the search on the GPU (gl_proximity.h) and widens here, over its trees' host copy.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/collision/bvh_upkeep.h"
#include "core/collision/collision_data.h"
#include "core/collision/proximity.h"
#include "cpu/cpu_bvh_trees.h"
#include "cpu/executor.h"

namespace deformcd::cpu {

class CpuProximity {
 public:
  /// Over the trees of `trees` (and their faces and meshes), which must outlive this object and
  /// hold trees now; their topology may change between searches (a rebuild). `mesh_pairs`: the
  /// collision data's mesh pairs, which searches name by index.
  CpuProximity(const collision::BvhUpkeep& trees, std::vector<gpu::BodyPair> mesh_pairs,
               std::shared_ptr<Executor> executor);

  /// The candidates whose boxes, swept from `positions` along each vertex's `motion` (null: no
  /// motion) and grown by each vertex's reach (>= 0), overlap and whose primitives' distance is
  /// within the two reaches (emit_face_pair_candidates), over the mesh pairs `mesh_pairs`
  /// (indices into the data's mesh pairs, ascending), mesh pair by mesh pair, then by the
  /// querying face of the pair's first mesh. With `distances`, each candidate's primitives'
  /// distance on `positions` (primitive_distance) in the same order.
  [[nodiscard]] std::vector<collision::ProximityCandidate> find(
      collision::VertexPositions positions, collision::VertexPositions motion,
      collision::VertexReach reach, std::span<const std::uint32_t> mesh_pairs,
      std::vector<float>* distances = nullptr);
  /// After a search over the same positions, motion and mesh pairs, whose reaches have since
  /// been raised for the vertices of `widened` (mesh, vertex): the candidates find() would now
  /// give that involve one of them, with their distances in `distances`. Only the faces that
  /// have one of them as a corner are swept again and query the trees, and of their face pairs
  /// only the candidates involving a widened vertex are tested. Ordered by face pair (mesh pair
  /// by mesh pair, then by the pair's two faces), whatever the thread count and the trees.
  /// The boxes are the last find()'s or widen()'s, unless the trees' topology has changed
  /// since or forget_boxes() was called: then they are refitted first.
  [[nodiscard]] std::vector<collision::ProximityCandidate> widen(
      collision::VertexPositions positions, collision::VertexPositions motion,
      collision::VertexReach reach, std::span<const std::uint32_t> mesh_pairs,
      std::span<const std::array<std::uint32_t, 2>> widened, std::vector<float>& distances);
  /// The search widen() follows ran elsewhere (on the GPU): this object's boxes are not its.
  void forget_boxes() { boxes_generation_ = 0; }

 private:
  /// Sweeps every face and fits the boxes (and the traversal's records of them) over the trees
  /// as they are now.
  void refit(collision::VertexPositions positions, collision::VertexPositions motion,
             collision::VertexReach reach);
  /// The records of the trees' internal nodes (children only; refit() writes their boxes).
  void make_records();
  /// The face pairs of the mesh pairs `mesh_pairs` whose boxes overlap, in find()'s order: mesh
  /// pair by mesh pair, by the face of the pair's first mesh (within one mesh the lower face),
  /// then by the other face's leaf.
  [[nodiscard]] std::vector<std::array<std::uint32_t, 2>> met_face_pairs(
      std::span<const std::uint32_t> mesh_pairs);
  /// Face `face` meets another face's box: its primitive boxes are needed. Any thread may call
  /// it, for any face, at once (each stores the same value).
  void want_primitives(std::uint32_t face) {
    std::atomic_ref<std::uint8_t> state(primitives_state_[face]);
    if (state.load(std::memory_order_relaxed) == kPrimitivesStale)
      state.store(kPrimitivesWanted, std::memory_order_relaxed);
  }
  /// Sweeps the primitives of the faces wanted since the last call (sweep_primitives).
  void sweep_primitives_of_met_faces();
  /// Asks for face `face`'s swept corners, box and primitive boxes to be brought into the
  /// cache. The emission meets the second faces of its face pairs in their leaves' order, not
  /// in the order of these arrays, and waited on each one's first box load (`perf annotate`:
  /// the two hottest instructions of the emission); fetched kPrefetchAhead pairs early, a
  /// body's search against itself took about 6 % less time on the impact (bench_proximity).
  void prefetch_face(std::uint32_t face) const {
    const auto* swept = reinterpret_cast<const char*>(&swept_[face]);
    const auto* primitives = reinterpret_cast<const char*>(&primitives_[face]);
    for (std::size_t line = 0; line < sizeof(collision::SweptFace); line += 64u)
      __builtin_prefetch(swept + line);
    for (std::size_t line = 0; line < sizeof(collision::SweptPrimitives); line += 64u)
      __builtin_prefetch(primitives + line);
  }
  static constexpr std::size_t kPrefetchAhead = 8;

  // primitives_state_: a face's primitives_ entry is from before its last sweep, is wanted by
  // a face pair of the search, or is swept from its swept_ entry.
  static constexpr std::uint8_t kPrimitivesStale = 0, kPrimitivesWanted = 1, kPrimitivesSwept = 2;

  const collision::BvhUpkeep& trees_;
  std::vector<gpu::BodyPair> mesh_pairs_;
  std::vector<std::uint32_t> owners_;
  std::vector<gpu::Box> boxes_;           // per node: swept over the period, grown by the reaches
  std::uint64_t boxes_generation_ = 0;    // the trees' generation boxes_ fit (0: none)
  std::vector<std::uint32_t> leaf_of_;    // per face (layout order): its tree's leaf node
  std::vector<ChildBoxes> records_;       // per internal node: its children's boxes_ (traversal)
  std::vector<std::uint32_t> record_of_;  // per node: its record, kBvhInternal for a leaf
  std::uint64_t records_generation_ = 0;  // the trees' generation records_ fit (0: none)
  std::vector<collision::SweptFace> swept_;  // per face (layout order): of the last search
  std::vector<collision::SweptPrimitives> primitives_;  // per face: of the faces met (state)
  std::vector<std::uint8_t> primitives_state_;          // per face: kPrimitives*
  std::vector<std::uint32_t> vertex_faces_;  // per mesh vertex (vertex_first_ order): CSR faces
  std::vector<std::uint32_t> vertex_face_offset_;
  std::vector<std::uint32_t> vertex_first_;  // per mesh: its first vertex in that order
  std::shared_ptr<Executor> executor_;
};

}  // namespace deformcd::cpu
