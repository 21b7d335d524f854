#pragma once
/// \file intersection_census.h
/// A count of how a set of closed surfaces intersect, that folding cannot hide (issue 33): the
/// intersecting triangle pairs between meshes, the intersecting pairs of each mesh with itself,
/// and the surface vertices of one mesh inside another closed mesh. A contact response may keep
/// every pair of different bodies apart while a soft body folds its surface through itself and
/// the other body slides through the fold; the self pairs and the inside vertices see that.
///
///     deformcd::IntersectionCounter counter(meshes);        // once: topology only
///     deformcd::IntersectionCensus c = counter.count(positions);  // every frame
///     if (c.any()) ...
///
/// On the CPU, deterministic: the same counts on every thread count.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/detector.h"

namespace deformcd {

/// What IntersectionCounter::count found on one set of positions.
struct IntersectionCensus {
  /// Intersecting triangle pairs of two different meshes.
  std::uint64_t between_pairs = 0;
  /// Intersecting triangle pairs of one mesh with itself; triangles sharing an edge are never
  /// a pair, triangles sharing one vertex are when they also meet elsewhere (as the detector's
  /// self-collision decides, by topology).
  std::uint64_t self_pairs = 0;
  /// Surface vertices (corners of a mesh's triangles) strictly inside at least one other mesh
  /// that is closed (every edge in exactly two of its triangles). A vertex on the other
  /// surface is not inside.
  std::uint64_t inside_vertices = 0;

  /// Whether anything intersects: a pair between meshes, a pair within one, or a vertex inside.
  [[nodiscard]] bool any() const {
    return between_pairs != 0 || self_pairs != 0 || inside_vertices != 0;
  }
};

/// Counts intersections of a fixed set of meshes at positions given per call.
class IntersectionCounter {
 public:
  /// The meshes' triangles (their self_collision flags are ignored: every mesh is tested with
  /// itself). Throws InputError as Detector does for a bad mesh. `threads`: CPU threads of the
  /// triangle-pair search, 0 every core; the counts do not depend on it.
  explicit IntersectionCounter(std::vector<CollisionMesh> meshes, int threads = 1);
  ~IntersectionCounter();
  /// Movable (the meshes and the detector move along); not copyable.
  IntersectionCounter(IntersectionCounter&&) noexcept;
  /// Movable; not copyable.
  IntersectionCounter& operator=(IntersectionCounter&&) noexcept;

  /// The number of meshes given to the constructor.
  [[nodiscard]] std::size_t mesh_count() const;
  /// Whether mesh `mesh` is closed, so that vertices of the others can be inside it.
  [[nodiscard]] bool closed(std::size_t mesh) const;
  /// The census on `positions` (one span per mesh, each vertex_count long; InputError
  /// otherwise, or for a non-finite position).
  [[nodiscard]] IntersectionCensus count(std::span<const std::span<const glm::vec3>> positions);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deformcd
