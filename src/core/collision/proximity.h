#pragma once
// Proximity candidates (issue 12): the vertex-face and edge-edge pairs whose bounding boxes,
// swept along their vertices' motion over a period, come within a reach of each other, found
// from face pairs of swept and inflated boxes. The per-face-pair step
// is a pure function here, which the CPU backend (src/cpu/cpu_proximity.cpp) calls and which a
// GLSL version must mirror.
//
// Every vertex and edge is emitted from one face only, its owner (the lowest-numbered face of
// its mesh containing it), so no pair appears twice: a vertex's or an edge's box lies inside
// every face's box containing it, so when it comes within reach of a face (or edge), so does
// its owner's box, and the owner's face pair is found.

#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/broad_phase.h"
#include "core/collision/primitive_distance.h"
#include "core/collision/vertex_positions.h"
#include "deformcd/gpu_layout.h"

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

/// Corner (k + 1) % 3, the other end of edge k.
inline constexpr std::array<std::uint32_t, 3> kNextCorner{1u, 2u, 0u};

/// Per face (layout order), which of its corners and edges it owns. `faces` mesh by mesh, with
/// Face::body the mesh and indices local to it.
[[nodiscard]] std::vector<std::uint32_t> primitive_owners(const std::vector<gpu::Face>& faces);

/// The box of `count` points, grown by `reach` on every side.
[[nodiscard]] inline gpu::Box reach_box(const glm::vec3* points, std::uint32_t count, float reach) {
  glm::vec3 lo = points[0], hi = points[0];
  for (std::uint32_t i = 1; i < count; ++i) {
    lo = glm::min(lo, points[i]);
    hi = glm::max(hi, points[i]);
  }
  return {glm::vec4(lo - reach, 0.0f), glm::vec4(hi + reach, 0.0f)};
}

/// Vertex `vertex` of mesh `mesh`'s motion over the search's period (m); zero without one.
[[nodiscard]] inline glm::vec3 vertex_motion(VertexPositions motion, std::uint32_t mesh,
                                             std::uint32_t vertex) {
  return motion == nullptr ? glm::vec3(0.0f) : vertex_position(motion, mesh, vertex);
}

/// Face f's corners where the period starts (out[0..2], in the order a, b, c) and where their
/// motion takes them (out[3..5]): every primitive of the face is swept between the two.
inline void swept_face_vertices(VertexPositions positions, VertexPositions motion,
                                const gpu::Face& f, glm::vec3 out[6]) {
  face_vertices(positions, f, out);
  for (std::uint32_t k = 0; k < 3u; ++k)
    out[3u + k] = out[k] + vertex_motion(motion, f.body, face_corner(f, k));
}

/// Whether candidate c pairs neighbours on one mesh's surface, never a proximity pair: a vertex
/// with a face it is a corner of, or two edges sharing a vertex. This is the rule of Bridson,
/// Fedkiw and Anderson 2002 and of cloth codes since, at the level of primitives: faces that
/// merely share a corner are not left out, since where a surface is crushed (a tight fold) a
/// face's other primitives can pass through its neighbours' and only these pairs see it.
[[nodiscard]] inline bool surface_neighbours(const ProximityCandidate& c) {
  const std::array<std::uint32_t, 4>& v = c.vertices;
  if (c.mesh_a != c.mesh_b) return false;
  if (c.kind == gpu::kContactVertexFace) return v[0] == v[1] || v[0] == v[2] || v[0] == v[3];
  return v[0] == v[2] || v[0] == v[3] || v[1] == v[2] || v[1] == v[3];
}

/// Emits candidate c, its primitives' vertices at x where the period starts and at `end` where
/// their motion ends (in primitive_distance's order), unless its primitives are surface
/// neighbours or their distance at the start, less what the motions can close of it over the
/// period, exceeds `reach`; `emit` gets the candidate and that distance (primitive_distance).
/// The GLSL mirror's proximity_emit takes the candidate alone.
template <class Emit>
void emit_if_within_reach(const ProximityCandidate& c, const glm::vec3 x[4], const glm::vec3 end[4],
                          float reach, const Emit& emit) {
  if (surface_neighbours(c)) return;
  const glm::vec3 motion[4] = {end[0] - x[0], end[1] - x[1], end[2] - x[2], end[3] - x[3]};
  float distance = 0.0f;
  if (primitives_within(c.kind, x, closing_speed(c.kind, motion), reach, &distance))
    emit(c, distance);
}

/// Every mesh's per-vertex reaches, indexed by mesh (Face::body): vertex i's is [mesh][i].
using VertexReach = const float* const*;

/// The reach of face f's corners (out[0..2]) and the face's (the largest, returned).
inline float face_reaches(VertexReach reach, const gpu::Face& f, float out[3]) {
  out[0] = reach[f.body][f.a];
  out[1] = reach[f.body][f.b];
  out[2] = reach[f.body][f.c];
  return glm::max(out[0], glm::max(out[1], out[2]));
}

/// A face over the period: its corners where the period starts and where their motion takes
/// them (swept_face_vertices), their reaches, and its box grown by the largest (the box its
/// tree's leaf and its queries use). A search sweeps each face once, not once per face pair.
struct SweptFace {
  glm::vec3 x[6];    ///< corners a, b, c at the period's start, then at its end
  float reach[3];    ///< the corners' reaches
  float face_reach;  ///< the largest of them
  gpu::Box box;      ///< x[0..5] grown by face_reach
};

/// Face f swept over the period (SweptFace).
inline SweptFace sweep_face(VertexPositions positions, VertexPositions motion, VertexReach reach,
                            const gpu::Face& f) {
  SweptFace s;
  swept_face_vertices(positions, motion, f, s.x);
  s.face_reach = face_reaches(reach, f, s.reach);
  s.box = reach_box(s.x, 6u, s.face_reach);
  return s;
}

/// The boxes of a swept face's primitives: each corner's path grown by its reach, each edge's
/// sweep (the union of its corners' paths) grown by the larger of its corners' reaches. Only
/// the faces that meet another face's box need them (the search sweeps those once).
struct SweptPrimitives {
  gpu::Box vertex_box[3];  ///< corner k's path (x[k], x[3 + k])
  gpu::Box edge_box[3];    ///< edge k, from corner k to corner (k + 1) % 3
};

/// The primitive boxes of swept face s (SweptPrimitives). The bounds are min / max of the
/// corners and one addition or subtraction of a reach, exact operations.
inline SweptPrimitives sweep_primitives(const SweptFace& s) {
  SweptPrimitives p;
  glm::vec3 lo[3], hi[3];
  for (std::uint32_t k = 0; k < 3u; ++k) {
    lo[k] = glm::min(s.x[k], s.x[3u + k]);
    hi[k] = glm::max(s.x[k], s.x[3u + k]);
    p.vertex_box[k] = {glm::vec4(lo[k] - s.reach[k], 0.0f), glm::vec4(hi[k] + s.reach[k], 0.0f)};
  }
  for (std::uint32_t k = 0; k < 3u; ++k) {
    const std::uint32_t k1 = kNextCorner[k];
    const float r = glm::max(s.reach[k], s.reach[k1]);
    p.edge_box[k] = {glm::vec4(glm::min(lo[k], lo[k1]) - r, 0.0f),
                     glm::vec4(glm::max(hi[k], hi[k1]) + r, 0.0f)};
  }
  return p;
}

/// A filter that keeps every candidate (emit_face_pair_candidates' default).
struct EveryCandidate {
  constexpr bool operator()(const ProximityCandidate& /*candidate*/) const { return true; }
};

/// The candidates of one face pair (fa of mesh a, fb of mesh b, swept as sa and sb with
/// primitive boxes pa and pb, whose boxes overlap; for one mesh, fa < fb, and pairs of surface
/// neighbours are left out, so that two faces sharing a corner still give their other primitives'
/// pairs) in a fixed order: fa's owned vertices against fb, fb's owned vertices against fa, then
/// fa's owned edges against fb's. Each vertex moves linearly by its motion over the period and may
/// stray from that path by its reach: a primitive's box spans both ends of its path (swept) and is
/// grown by its reach (a vertex's own, the largest of an edge's or a face's vertices'); a pair
/// whose boxes overlap is kept unless its distance where the period starts, less what the motions
/// can close of it (closing_speed), exceeds the sum of the two reaches. A pair that comes within
/// that sum at some moment of the period is always emitted. Only the candidates `wanted` keeps
/// are looked at (a widened search keeps those of some vertices; the GLSL mirror, which
/// always searches whole, has no filter).
template <class Emit, class Wanted = EveryCandidate>
void emit_face_pair_candidates(const gpu::Face& fa, const SweptFace& sa, const SweptPrimitives& pa,
                               std::uint32_t index_a, std::uint32_t owners_a, const gpu::Face& fb,
                               const SweptFace& sb, const SweptPrimitives& pb,
                               std::uint32_t index_b, std::uint32_t owners_b, const Emit& emit,
                               const Wanted& wanted = {}) {
  const glm::vec3* xa = sa.x;
  const glm::vec3* xb = sb.x;
  for (std::uint32_t k = 0; k < 3u; ++k) {
    if ((owners_a & (kOwnsVertex0 << k)) == 0u || !boxes_overlap(pa.vertex_box[k], sb.box))
      continue;
    const ProximityCandidate c{
        gpu::kContactVertexFace, fa.body, fb.body, index_b, {face_corner(fa, k), fb.a, fb.b, fb.c}};
    if (wanted(c))
      emit_if_within_reach(c, std::array{xa[k], xb[0], xb[1], xb[2]}.data(),
                           std::array{xa[3u + k], xb[3], xb[4], xb[5]}.data(),
                           sa.reach[k] + sb.face_reach, emit);
  }
  for (std::uint32_t k = 0; k < 3u; ++k) {
    if ((owners_b & (kOwnsVertex0 << k)) == 0u || !boxes_overlap(pb.vertex_box[k], sa.box))
      continue;
    const ProximityCandidate c{
        gpu::kContactVertexFace, fb.body, fa.body, index_a, {face_corner(fb, k), fa.a, fa.b, fa.c}};
    if (wanted(c))
      emit_if_within_reach(c, std::array{xb[k], xa[0], xa[1], xa[2]}.data(),
                           std::array{xb[3u + k], xa[3], xa[4], xa[5]}.data(),
                           sb.reach[k] + sa.face_reach, emit);
  }
  // The owned edges' pairs, through the owner bits (a face owns 1.5 edges on average, so most of
  // the nine pairs are never looked at).
  for (std::uint32_t ea = (owners_a / kOwnsEdge0) & 7u; ea != 0u; ea &= ea - 1u) {
    const auto i = static_cast<std::uint32_t>(std::countr_zero(ea));
    const std::uint32_t i1 = kNextCorner[i];
    const float reach_a = glm::max(sa.reach[i], sa.reach[i1]);
    for (std::uint32_t eb = (owners_b / kOwnsEdge0) & 7u; eb != 0u; eb &= eb - 1u) {
      const auto j = static_cast<std::uint32_t>(std::countr_zero(eb));
      if (!boxes_overlap(pa.edge_box[i], pb.edge_box[j])) continue;
      const std::uint32_t j1 = kNextCorner[j];
      const float reach_b = glm::max(sb.reach[j], sb.reach[j1]);
      const ProximityCandidate c{
          gpu::kContactEdgeEdge,
          fa.body,
          fb.body,
          0u,
          {face_corner(fa, i), face_corner(fa, i1), face_corner(fb, j), face_corner(fb, j1)}};
      if (wanted(c))
        emit_if_within_reach(c, std::array{xa[i], xa[i1], xb[j], xb[j1]}.data(),
                             std::array{xa[3u + i], xa[3u + i1], xb[3u + j], xb[3u + j1]}.data(),
                             reach_a + reach_b, emit);
    }
  }
}

}  // namespace deformcd::collision
