#pragma once
// Proximity candidates (issue 12): the vertex-face and edge-edge pairs whose bounding boxes come
// within a reach of each other, found from face pairs of inflated boxes. The per-face-pair step
// is a pure function here, which the CPU backend (src/cpu/cpu_proximity.cpp) calls and which a
// GLSL version must mirror.
//
// Every vertex and edge is emitted from one face only, its owner (the lowest-numbered face of
// its mesh containing it), so no pair appears twice: a vertex's or an edge's box lies inside
// every face's box containing it, so when it comes within reach of a face (or edge), so does
// its owner's box, and the owner's face pair is found.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "broad_phase.h"
#include "deformcd/gpu_layout.h"
#include "vertex_positions.h"

namespace deformcd::collision {

/// One candidate, vertex indices local to their meshes: kContactVertexFace: vertex of mesh_a,
/// then the corners a, b, c of a face of mesh_b; kContactEdgeEdge: an edge of mesh_a, then an
/// edge of mesh_b. mesh_a == mesh_b for self-proximity.
struct ProximityCandidate {
  std::uint32_t kind;
  std::uint32_t mesh_a;
  std::uint32_t mesh_b;
  std::uint32_t face_b;  ///< kContactVertexFace: the face's index in the layout; else 0
  std::array<std::uint32_t, 4> vertices;

  friend bool operator==(const ProximityCandidate&, const ProximityCandidate&) = default;
  // clang-tidy's modernize-use-nullptr flags the defaulted <=> in every file that sorts these
  // (it sees the literal 0 that the synthesized comparison compares against): a false positive.
  // NOLINTNEXTLINE(modernize-use-nullptr)
  friend auto operator<=>(const ProximityCandidate&, const ProximityCandidate&) = default;
};

/// Owner bits of a face: bit k (0-2) when it owns corner k, bit 3 + k when it owns edge k
/// (edge k runs from corner k to corner (k + 1) % 3).
inline constexpr std::uint32_t kOwnsVertex0 = 1u;
inline constexpr std::uint32_t kOwnsEdge0 = 8u;

/// Per face (layout order), which of its corners and edges it owns. `faces` mesh by mesh, with
/// Face::body the mesh and indices local to it.
[[nodiscard]] std::vector<std::uint32_t> primitive_owners(const std::vector<gpu::Face>& faces);

/// The box of a point, or of a segment, or of a triangle, grown by `reach` on every side.
[[nodiscard]] inline gpu::Box reach_box(const glm::vec3* points, std::uint32_t count, float reach) {
  glm::vec3 lo = points[0], hi = points[0];
  for (std::uint32_t i = 1; i < count; ++i) {
    lo = glm::min(lo, points[i]);
    hi = glm::max(hi, points[i]);
  }
  return {glm::vec4(lo - reach, 0.0f), glm::vec4(hi + reach, 0.0f)};
}

/// `box` swept along `d`: the union of the box and the box moved by d.
[[nodiscard]] inline gpu::Box sweep_box(const gpu::Box& box, const glm::vec3& d) {
  return {glm::vec4(glm::vec3(box.min) + glm::min(d, glm::vec3(0.0f)), 0.0f),
          glm::vec4(glm::vec3(box.max) + glm::max(d, glm::vec3(0.0f)), 0.0f)};
}

/// Whether two faces of one mesh share a corner: their primitives are neighbours on the surface
/// and never a proximity pair.
[[nodiscard]] inline bool faces_share_vertex(const gpu::Face& a, const gpu::Face& b) {
  for (std::uint32_t i = 0; i < 3u; ++i) {
    const std::uint32_t v = face_corner(a, i);
    if (v == b.a || v == b.b || v == b.c) return true;
  }
  return false;
}

/// The candidates of one face pair (fa of mesh a, fb of mesh b, whose boxes grown by `reach`
/// overlap; for one mesh, fa < fb and the faces share no corner) in a fixed order: fa's owned
/// vertices against fb, fb's owned vertices against fa, then fa's owned edges against fb's.
/// `reach` is the sum of the two meshes' reaches and `sweep` mesh a's drift minus mesh b's over
/// the period: a primitive of fa (of fb) is grown by the reach and swept along sweep (along
/// -sweep), and tested against the other's plain box. Primitives moving apart from each
/// other along their meshes' drifts by less than their reaches are then always found.
template <class Emit>
void emit_face_pair_candidates(VertexPositions positions, const gpu::Face& fa,
                               std::uint32_t index_a, std::uint32_t owners_a, const gpu::Face& fb,
                               std::uint32_t index_b, std::uint32_t owners_b, float reach,
                               const glm::vec3& sweep, const Emit& emit) {
  glm::vec3 xa[3], xb[3];
  face_vertices(positions, fa, xa);
  face_vertices(positions, fb, xb);
  const gpu::Box box_a = reach_box(xa, 3u, 0.0f);
  const gpu::Box box_b = reach_box(xb, 3u, 0.0f);
  for (std::uint32_t k = 0; k < 3u; ++k) {
    if ((owners_a & (kOwnsVertex0 << k)) != 0u &&
        boxes_overlap(sweep_box(reach_box(&xa[k], 1u, reach), sweep), box_b))
      emit(ProximityCandidate{gpu::kContactVertexFace,
                              fa.body,
                              fb.body,
                              index_b,
                              {face_corner(fa, k), fb.a, fb.b, fb.c}});
  }
  for (std::uint32_t k = 0; k < 3u; ++k) {
    if ((owners_b & (kOwnsVertex0 << k)) != 0u &&
        boxes_overlap(sweep_box(reach_box(&xb[k], 1u, reach), -sweep), box_a))
      emit(ProximityCandidate{gpu::kContactVertexFace,
                              fb.body,
                              fa.body,
                              index_a,
                              {face_corner(fb, k), fa.a, fa.b, fa.c}});
  }
  for (std::uint32_t i = 0; i < 3u; ++i) {
    if ((owners_a & (kOwnsEdge0 << i)) == 0u) continue;
    const glm::vec3 edge_a[2] = {xa[i], xa[(i + 1u) % 3u]};
    const gpu::Box grown = sweep_box(reach_box(edge_a, 2u, reach), sweep);
    for (std::uint32_t j = 0; j < 3u; ++j) {
      if ((owners_b & (kOwnsEdge0 << j)) == 0u) continue;
      const glm::vec3 edge_b[2] = {xb[j], xb[(j + 1u) % 3u]};
      if (boxes_overlap(grown, reach_box(edge_b, 2u, 0.0f)))
        emit(ProximityCandidate{gpu::kContactEdgeEdge,
                                fa.body,
                                fb.body,
                                0u,
                                {face_corner(fa, i), face_corner(fa, (i + 1u) % 3u),
                                 face_corner(fb, j), face_corner(fb, (j + 1u) % 3u)}});
    }
  }
}

}  // namespace deformcd::collision
