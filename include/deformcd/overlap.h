#pragma once
/// \file overlap.h
/// How two closed surfaces overlap, for taking them apart (issue 33, deep overlap): the
/// direction that shrinks their common volume fastest, and each surface vertex of one that lies
/// inside the other with the triangle of the other it leaves through along that direction.
///
///     deformcd::OverlapFinder finder(meshes);                   // once: topology only
///     deformcd::Overlap o = finder.find(a, b, positions_a, positions_b);
///     for (const deformcd::PenetratingVertex& p : o.a_in_b) ...  // push p.vertex out, along
///                                                              // o.direction, past p.face
///
/// A contact between surface primitives sees only where two surfaces cross; a vertex deep inside
/// the other body has no primitive near it and stays inside. The direction is one per pair of
/// meshes, so every vertex of a body leaves the other on the same side: the nearest surface
/// point of each vertex (a signed distance's gradient) would take vertices past the other
/// body's middle out through its far side, and the bodies through each other.
///
/// Deterministic: one thread, a fixed summation order.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "deformcd/collision_mesh.h"

namespace deformcd {

/// A surface vertex of one mesh inside another, and where it leaves that mesh.
struct PenetratingVertex {
  std::uint32_t vertex = 0;  ///< the vertex (its index in its mesh)
  /// The triangle of the other mesh (its index in CollisionMesh::triangles) that the ray from
  /// the vertex along its way out (Overlap::direction, or its opposite) crosses first.
  std::uint32_t triangle = 0;
  float depth = 0.0f;  ///< the distance along that ray to the triangle
};

/// How mesh a and mesh b overlap (OverlapFinder::find).
struct Overlap {
  /// Unit: moving a along it (or b against it) shrinks the volume they share fastest, the flux
  /// of b's surface inside a less that of a's surface inside b. Zero when they do not overlap.
  glm::vec3 direction{0.0f};
  /// a's surface vertices inside b, ascending, each leaving b along +direction.
  std::vector<PenetratingVertex> a_in_b;
  /// b's surface vertices inside a, ascending, each leaving a along -direction.
  std::vector<PenetratingVertex> b_in_a;

  /// Whether a vertex of either mesh is inside the other.
  [[nodiscard]] bool any() const { return !a_in_b.empty() || !b_in_a.empty(); }
};

/// Finds how pairs of a fixed set of meshes overlap, at positions given per call.
class OverlapFinder {
 public:
  /// The meshes' triangles; each mesh's orientation is found from its signed volume at every
  /// call, so either winding works. Throws InputError for a triangle naming a vertex beyond
  /// vertex_count.
  explicit OverlapFinder(std::vector<CollisionMesh> meshes);
  ~OverlapFinder();
  /// Movable; not copyable.
  OverlapFinder(OverlapFinder&&) noexcept;
  /// Movable; not copyable.
  OverlapFinder& operator=(OverlapFinder&&) noexcept;

  /// The number of meshes given to the constructor.
  [[nodiscard]] std::size_t mesh_count() const;
  /// Whether mesh `mesh` is closed (every edge in exactly two of its triangles): only closed
  /// meshes have an inside.
  [[nodiscard]] bool closed(std::size_t mesh) const;
  /// How meshes a and b (a != b) overlap with their vertices at `a_positions` and `b_positions`
  /// (vertex_count long each). Nothing (any() false) when either is not closed. A vertex is
  /// inside as IntersectionCounter decides (certified ray parity); a vertex whose ray meets no
  /// triangle within rounding is left out. When the fluxes cancel (one mesh wholly inside the
  /// other), the direction is from b's surface vertices' centroid to a's (x when they
  /// coincide). Throws InputError for a bad mesh index, a wrong count or a non-finite position.
  [[nodiscard]] Overlap find(std::size_t a, std::size_t b, std::span<const glm::vec3> a_positions,
                             std::span<const glm::vec3> b_positions) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deformcd
