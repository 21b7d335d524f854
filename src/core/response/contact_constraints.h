#pragma once
// Contact response as pure per-element functions (issue 12), in passes per substep: each
// node's distance from its straight path (per node), which constraints are active (per
// constraint), each node's count of active contacts (per node: an integer, whatever the order),
// then sweeps over the active constraints (per constraint, colour by colour). The CPU backend
// calls these; shaders/response/*.glsl mirror them line for line, so both backends compute the
// same floating-point operations in the same order.
//
// A constraint couples four nodes with weights b (the gradient of its distance along its normal
// n is b_k n for node k) that sum to zero, so every correction w_k b_k lambda n, with w_k the
// inverse mass, conserves momentum. An iteration is a Gauss-Seidel sweep: the active
// constraints in colours (sweep_order.h: no two of one colour share a node, so a colour's
// constraints are solved in parallel and in any order with the same result), each solved on its
// nodes as the constraints before it left them and applied at once. A contact lends each of its
// nodes' other active contacts a share (mass splitting, Tonge, Benevolenski and Voroshilov
// 2012: node k weighs count_k x its inverse mass), so that the contacts of a node share its load
// and its slip evenly, as Coulomb's friction needs (a contact that took a node's whole load
// first left the others no friction cone); the volume constraints weigh their nodes' plain
// inverse masses. Each constraint keeps what it has given over a substep's iterations and
// corrects that total, clamped at zero, so that a correction the constraints after it made too
// much of is taken back (solve_contact). A sweep converged within the 8 iterations asked where
// the Jacobi iterations this replaced ran 16 on the impact
// (docs/notes/2026-12-07-gauss-seidel-probe.md).

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/collision/primitive_distance.h"
#include "core/sim/mass_spring.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::response {

/// Per-substep constants of the response.
struct ContactConstants {
  float h;                  ///< substep length, s
  float friction_static;    ///< Coulomb static coefficient (>= 0)
  float friction_dynamic;   ///< Coulomb dynamic coefficient (>= 0, <= friction_static)
  float restitution;        ///< 0: the approach speed is absorbed, 1: given back along n
  float max_untangle_step;  ///< m: most an untangling constraint moves its nodes per substep
  float elapsed;            ///< s: from the frame's start to the end of this substep
};

/// The plane projection of p on triangle (a, b, c) as barycentric weights (u, v, w),
/// u + v + w = 1 (negative outside the triangle); false for a degenerate triangle. T = float is
/// the constraints' (the GLSL mirror's); the world's search asks in double
/// (ContactResponse::over_a_face_beside).
template <class T>
inline bool plane_barycentric(const glm::vec<3, T>& p, const glm::vec<3, T>& a,
                              const glm::vec<3, T>& b, const glm::vec<3, T>& c,
                              glm::vec<3, T>& uvw) {
  const glm::vec<3, T> ab = b - a, ac = c - a, ap = p - a;
  const T d00 = glm::dot(ab, ab), d01 = glm::dot(ab, ac), d11 = glm::dot(ac, ac);
  const T d20 = glm::dot(ap, ab), d21 = glm::dot(ap, ac);
  const T denominator = d00 * d11 - d01 * d01;
  if (!(denominator > T(1e-12) * d00 * d11)) return false;
  const T v = (d11 * d20 - d01 * d21) / denominator;
  const T w = (d00 * d21 - d01 * d20) / denominator;
  uvw = glm::vec<3, T>(T(1) - v - w, v, w);
  return true;
}

/// A new vertex-face constraint's side (ContactPair::side): 1 when vertex x[0] is in front of
/// face (x[1], x[2], x[3]), on the side its normal (counter-clockwise corners) points to, else
/// 0. The world's search calls it on the host (for both backends), so no shader mirrors it.
inline float vertex_face_side(const glm::vec3 x[4]) {
  return glm::dot(x[0] - x[1], glm::cross(x[2] - x[1], x[3] - x[1])) > 0.0f ? 1.0f : 0.0f;
}

/// Which side of edge (x[2], x[3])'s line edge (x[0], x[1])'s line passes on: the sign of
/// (x[0] - x[2]) . (da x db), 1 or -1, where the edges are more than about 6 degrees from
/// parallel; else 0 (no side). The sign turns when the edges go through each other, and also
/// when they pass around an end or their directions turn through parallel (edges_went_through
/// tells these apart).
inline float edge_line_side(const glm::vec3 x[4]) {
  const glm::vec3 da = x[1] - x[0], db = x[3] - x[2];
  const glm::vec3 normal = glm::cross(da, db);
  if (!(glm::dot(normal, normal) > 1e-2f * glm::dot(da, da) * glm::dot(db, db))) return 0.0f;
  return glm::dot(x[0] - x[2], normal) > 0.0f ? 1.0f : -1.0f;
}

/// edge_line_side where the edges' closest points (at edge parameters s and t) are inside both
/// edges, else 0: the side their segments pass each other on.
inline float edge_edge_side(const glm::vec3 x[4], float s, float t) {
  if (!(s > 0.0f && s < 1.0f && t > 0.0f && t < 1.0f)) return 0.0f;
  return edge_line_side(x);
}

/// A new edge-edge constraint's side (ContactPair::side): edge_edge_side where its window
/// starts (0 where the closest points are an end then). The world's search calls it on the
/// host (for both backends), so no shader mirrors it.
inline float edge_edge_start_side(const glm::vec3 x[4]) {
  float s = 0.0f, t = 0.0f;
  if (!collision::segment_closest_parameters<float>(x[0], x[1], x[2], x[3], s, t)) return 0.0f;
  return edge_edge_side(x, s, t);
}

/// Whether contact_geometry reads where the constraint's nodes started the window (its `start`):
/// only edge-edge constraints with a side do, so the passes load those positions for them alone.
inline bool reads_window_start(const gpu::ContactPair& pair) {
  return pair.kind == gpu::kContactEdgeEdge && pair.side != 0.0f;
}

/// The four corners of an edge pair a share `tau` of the way from where the window started
/// (`start`) to where they are now (x), into p; returns their lines' offset along da x db there
/// (the sign edge_edge_side takes).
inline float edge_offset_along_the_way(const glm::vec3 start[4], const glm::vec3 x[4], float tau,
                                       glm::vec3 p[4]) {
  for (int k = 0; k < 4; ++k)
    p[k] = start[k] + tau * (x[k] - start[k]);
  return glm::dot(p[0] - p[2], glm::cross(p[1] - p[0], p[3] - p[2]));
}

/// The bisection steps of edges_went_through: the moment found to 2^-24 of the way from the
/// window's start.
inline constexpr int kThroughBisections = 24;

/// Whether edges on one side of each other where the window started (`start`, offset sign
/// `side`) and on the other now (x) went through each other: along the straight way between,
/// where their lines meet (the offset, a cubic in the way, turns sign: found by bisection), the
/// meeting point is inside both edges and they are not parallel there. Edges that passed
/// around an end, or whose directions turned through parallel (two edges of bodies rolling
/// over each other), change sides too, but their segments never met: pushed back along their
/// starting side they would be pushed through each other.
inline bool edges_went_through(const glm::vec3 start[4], const glm::vec3 x[4], float side) {
  glm::vec3 p[4];
  float before = 0.0f, after = 1.0f;
  for (int i = 0; i < kThroughBisections; ++i) {
    const float middle = 0.5f * (before + after);
    if (edge_offset_along_the_way(start, x, middle, p) * side > 0.0f) {
      before = middle;
    } else {
      after = middle;
    }
  }
  (void)edge_offset_along_the_way(start, x, after, p);
  float s = 0.0f, t = 0.0f;
  if (!collision::segment_closest_parameters<float>(p[0], p[1], p[2], p[3], s, t)) return false;
  return edge_edge_side(p, s, t) != 0.0f;
}

/// The geometry of one constraint on the current positions x (where the window started:
/// `start`, read only where reads_window_start says): normal n, weights b (sum 0), and C, the
/// distance along n minus the thickness (the constraint wants C >= 0). False when the
/// constraint does not apply now (vertex beside the face, beyond its band, degenerate).
inline bool contact_geometry(const gpu::ContactPair& pair, const glm::vec3 x[4],
                             const glm::vec3 start[4], glm::vec3& n, float b[4], float& c) {
  if (pair.kind == gpu::kContactEdgeEdge) {
    float s = 0.0f, t = 0.0f;
    if (!collision::segment_closest_parameters<float>(x[0], x[1], x[2], x[3], s, t)) return false;
    const glm::vec3 d = (x[0] + s * (x[1] - x[0])) - (x[2] + t * (x[3] - x[2]));
    float distance = std::sqrt(glm::dot(d, d));
    if (!(distance > 1e-7f * pair.thickness)) return false;  // crossing: no direction
    n = d / distance;
    // Edges that passed each other on one side where the window started (pair.side) and have
    // gone through each other since: the closest points' difference has turned
    // over, and along it the constraint would hold them crossed. Their distance counts as
    // negative, which takes them back to their starting side, to the hold depth (at least the
    // thickness; deeper is a tunnel the untangling constraints resolve).
    // Why: the lion of the impact folded where the edges of a vertex's fan passed through an
    // edge of the body's own surface that its contacts held at a thin thickness (1.5 mm), once
    // they came within one substep's motion of it (docs/notes/2026-12-06-edge-sides.md).
    if (pair.side != 0.0f && edge_edge_side(x, s, t) == -pair.side &&
        edges_went_through(start, x, pair.side)) {
      if (distance > glm::max(pair.thickness, pair.hold_depth)) return false;
      n = -n;
      distance = -distance;
    }
    b[0] = 1.0f - s;
    b[1] = s;
    b[2] = -(1.0f - t);
    b[3] = -t;
    c = distance - pair.thickness;
    return true;
  }
  // Vertex x[0] against face (x[1], x[2], x[3]), along the face's outward normal.
  const glm::vec3 normal = glm::cross(x[2] - x[1], x[3] - x[1]);
  const float area2 = std::sqrt(glm::dot(normal, normal));
  glm::vec3 uvw;
  if (!(area2 > 0.0f) || !plane_barycentric(x[0], x[1], x[2], x[3], uvw)) return false;
  n = normal / area2;
  const float height = glm::dot(x[0] - x[1], n);
  if (pair.kind == gpu::kContactVertexFace) {
    // Only where the vertex lies over the face, started the window in front of it, and is not
    // deeper behind it than the thickness. A vertex that started behind the face is on the far
    // side of a thin part (in front of the face on the part's other side) or inside the body,
    // where the untangling constraints take it out: held in front of this face, it was pushed
    // against the other face's constraint every projection, and more projections pushed it
    // through one of them (on the impact scene with 5 perturbed starts, 8 projections left
    // 75 of 600 frames intersecting and 16 left 203; with this rule, none). Deeper than the
    // hold depth (the thickness, or a self pair's uncut thickness: ContactPair::hold_depth) is
    // a tunnel the untangling constraints resolve.
    if (uvw.x < 0.0f || uvw.y < 0.0f || uvw.z < 0.0f) return false;
    if (!(pair.side > 0.0f) || height < -glm::max(pair.thickness, pair.hold_depth)) return false;
  } else {
    // Untangling (kContactUntangle): the vertex of an intersecting face, pushed out of the
    // other body through this face's plane; weights clamped into the face.
    uvw = glm::clamp(uvw, 0.0f, 1.0f);
    uvw /= uvw.x + uvw.y + uvw.z;
  }
  b[0] = 1.0f;
  b[1] = -uvw.x;
  b[2] = -uvw.y;
  b[3] = -uvw.z;
  c = height - pair.thickness;
  return true;
}

/// How far a node is from its straight path: its position against where the search window's
/// start (frame_start.xyz) carried along its path velocity (node_motion.xyz) puts it after
/// `elapsed` seconds.
inline float path_deviation(const glm::vec3& position, const glm::vec4& frame_start,
                            const glm::vec4& node_motion, float elapsed) {
  const glm::vec3 centre = glm::vec3(frame_start) + glm::vec3(node_motion) * elapsed;
  const glm::vec3 moved = position - centre;
  return std::sqrt(glm::dot(moved, moved));
}

/// What the deviation pass records of a node at a projection's start (gpu::kProjectionStart):
/// xyz its position less h x its velocity, which velocity corrections leave as it is (they move
/// the node by their change x h) and only position corrections move, so that a contact sees how
/// far pushes (its neighbours', the volume floor's) have carried its point (solve_contact's
/// hold); w its distance from its straight path (path_deviation), which the activity pass reads.
inline glm::vec4 projection_start(const glm::vec4& position, const glm::vec4& velocity, float h,
                                  const glm::vec4& frame_start, const glm::vec4& node_motion,
                                  float elapsed) {
  const glm::vec3 base = glm::vec3(position) - h * glm::vec3(velocity);
  return glm::vec4(base, path_deviation(glm::vec3(position), frame_start, node_motion, elapsed));
}

/// Whether a constraint may act `elapsed` seconds into its search window, its nodes
/// deviation[k] from their straight paths: along the paths its distance shrinks by at most
/// closing_speed x elapsed, and each side's deviation takes at most that side's largest off it.
/// A constraint that is not awake is inactive (its distance is still above its thickness), so
/// the activity pass need not look at its geometry. Untangling constraints (gap -inf) are
/// always awake. The comparison keeps a margin of 1e-4 of the thickness for rounding.
inline bool contact_awake(const gpu::ContactPair& pair, const float deviation[4], float elapsed) {
  const float closest = pair.gap - pair.closing_speed * elapsed;
  return !(closest > collision::largest_per_side(pair.kind, deviation) + 1e-4f * pair.thickness);
}

/// A node's slide stamp (gpu::kNodeSlid) before any of its contacts slid: no projection counts
/// to it (the backends count projections from 1).
inline constexpr std::uint32_t kNeverSlid = 0xFFFFFFFFu;

/// slid_before's answers: none, some or all of a contact's free nodes had a contact slide in
/// the substep before.
inline constexpr std::uint32_t kNoneSlid = 0u;
inline constexpr std::uint32_t kSomeSlid = 1u;
inline constexpr std::uint32_t kAllSlid = 2u;

/// How many of a contact's free nodes (inverse mass position[k].w > 0) had a contact slide in
/// the substep before projection `substep` (slid[k], their stamps): kAllSlid, kSomeSlid or
/// kNoneSlid (also for a contact without free nodes). A contact slides on (solve_contact's
/// `was_sliding`) only where all did: a contact between a sliding body and one its points
/// stick to shares no free node with the other side's other contacts, and a body whose points
/// all slide keeps its contacts sliding; one free node's stamp alone spread a slide from
/// contact to contact over a whole face and let a block held at static 0.7 go. It holds its
/// point (the hold) only where none did: on a sliding block the contacts that stick for a
/// substep (new ones at its front, where its nodes climb onto the next faces) held the block
/// back, 1.313 m against 1.330 m without the hold in 3 s (Coulomb 1.460 m).
inline std::uint32_t slid_before(const glm::vec4 position[4], const std::uint32_t slid[4],
                                 std::uint32_t substep) {
  std::uint32_t free_nodes = 0u, slid_nodes = 0u;
  for (int i = 0; i < 4; ++i) {
    if (!(position[i].w > 0.0f)) continue;
    ++free_nodes;
    if (slid[i] + 1u == substep) ++slid_nodes;
  }
  if (slid_nodes == 0u) return kNoneSlid;
  return slid_nodes == free_nodes ? kAllSlid : kSomeSlid;
}

/// The sum of the absolute values of v's components: at least its length, without a root.
inline float abs_sum(const glm::vec3& v) {
  return (std::abs(v.x) + std::abs(v.y)) + std::abs(v.z);
}

/// Whether a constraint's primitives are surely farther apart than its thickness, by a bound
/// that takes no division or square root: the distance between the edges' lines (at most the
/// segments'), or the vertex's height over the face's plane (what contact_geometry's C
/// measures). The activity pass asks it before contact_geometry: most awake constraints are
/// near, not within their thickness (on the impact scene about 4,000 awake a substep against
/// 290 acting; this clears 58 % of them), and their geometry's divisions and roots cost several
/// times this. The margin, 1e-3 of the thickness, 1e-4 of the lengths the bound is made of and
/// 1e-6 of the coordinates (where contact_geometry's points round), exceeds the rounding of
/// both, so it never clears a constraint whose geometry would give C < 0. Edges within about 6
/// degrees of parallel get no bound from their lines.
inline bool contact_clear(const gpu::ContactPair& pair, const glm::vec3 x[4]) {
  if (pair.kind == gpu::kContactEdgeEdge) {
    const glm::vec3 da = x[1] - x[0], db = x[3] - x[2], r = x[0] - x[2];
    const glm::vec3 normal = glm::cross(da, db);
    const float normal2 = glm::dot(normal, normal);
    if (!(normal2 > 1e-2f * glm::dot(da, da) * glm::dot(db, db))) return false;
    const float along = glm::dot(r, normal);
    // On the other side of their starting one (pair.side) the edges may have gone through each
    // other: contact_geometry decides.
    if (along * pair.side < 0.0f) return false;
    const float limit =
        1.001f * pair.thickness + 1e-4f * abs_sum(r) + 1e-6f * (abs_sum(x[0]) + abs_sum(x[2]));
    return along * along > limit * limit * normal2;
  }
  const glm::vec3 normal = glm::cross(x[2] - x[1], x[3] - x[1]);
  const glm::vec3 offset = x[0] - x[1];
  const float height = glm::dot(offset, normal);
  const float limit = 1.001f * pair.thickness + 1e-4f * abs_sum(offset) + 1e-6f * abs_sum(x[1]);
  return height > 0.0f && height * height > limit * limit * glm::dot(normal, normal);
}

/// A volume constraint acts from kVolumeWatch x its floor down (volume_watched), not only
/// below it: the activity pass fixes a projection's active set, and contacts acting in its
/// iterations pushed the nodes of tetrahedra still above their floor through the opposite face
/// with nothing to stop them. The pile: frames with inverted tetrahedra 460 of 480 (at most 17
/// at once), and a dragon's thin fin (a tetrahedron with two faces on the surface) taken
/// through itself at frames 49 and 51; watched from twice the floor: 126 (at most 5), none
/// through. Over the pile's first 60 frames (inverted tetrahedra summed over the frames: 222
/// unwatched, 81 from twice the floor) 1.5x gave 46 but let the stack's bodies intersect at
/// frame 44; 3x 125, every tetrahedron 161 and two frames through (likely: an idle constraint
/// still counts in its nodes' mass splitting). Above the floor a constraint holds only
/// collapse faster than reaches the floor within the substep (solve_volume).
inline constexpr float kVolumeWatch = 2.0f;

/// The activity pass of a contact (every kind but kContactVolume): whether it acts now (its
/// distance along n is below its thickness), from the current positions.
inline bool contact_active(const gpu::ContactPair& pair, const glm::vec4 position[4],
                           const glm::vec3 start[4]) {
  const glm::vec3 x[4] = {glm::vec3(position[0]), glm::vec3(position[1]), glm::vec3(position[2]),
                          glm::vec3(position[3])};
  if (contact_clear(pair, x)) return false;
  glm::vec3 n(0.0f);
  float b[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  float c = 0.0f;
  return contact_geometry(pair, x, start, n, b, c) && c < 0.0f;
}

/// Whether an active contact guards its corners' volume constraints (volume_watched): a self
/// pair whose thickness the rest-distance rule cut to half its rest distance (its hold depth,
/// the body's thickness, is deeper). Such a pair joins two parts of a body that lie close at
/// rest, across a thin sliver: a cap tetrahedron (two faces on the surface, 0.66 mm high under
/// 89 mm edges on the armadillo's ear) was turned inside out within one projection, 2.05x its
/// rest volume to -1.50x, by the self vertex-face pair of its own corner, while its floor was
/// not watched (docs/notes/2026-12-07-mass-floor-slivers.md).
inline bool guards_volumes(const gpu::ContactPair& pair) {
  return (pair.kind == gpu::kContactVertexFace || pair.kind == gpu::kContactEdgeEdge) &&
         pair.thickness < pair.hold_depth;
}

/// The activity pass of a volume constraint: whether it acts now. Every one acts below
/// kVolumeWatch x its floor. A thin one (pair.side 1: lower at rest than its body's thickness,
/// which motion-bounded substeps keep a node from crossing within one) also acts when a corner
/// is `guarded` (named this projection by an active contact that guards_volumes), and when it
/// would be below the watch after one substep of its collapse (the volume's rate, sum of
/// g_k . v_k, when negative): the armadillo's other cap sliver went from 6.5x its rest volume
/// to 0.85x in five substeps with no constraint on its corners, then to -0.23x, inside out
/// before its floor was watched. Both rules on every tetrahedron held the 26 perturbed impact
/// starts too, but on the pile (480 frames, node mass floor 0.3) took 23 % more iterations, 5.6x
/// the frames with an inverted tetrahedron and 100 more frames to fall asleep: the bodies rest
/// on many guards, and tetrahedra compressed near their watch are woken by their jitter.
/// Watched, a constraint above its floor holds only collapse faster than reaches the floor
/// within the substep (solve_volume).
inline bool volume_watched(const gpu::ContactPair& pair, const glm::vec4 position[4],
                           const glm::vec4 velocity[4], float h, bool guarded) {
  const bool thin = pair.side > 0.0f;
  if (thin && guarded) return true;
  const glm::vec3 x[4] = {glm::vec3(position[0]), glm::vec3(position[1]), glm::vec3(position[2]),
                          glm::vec3(position[3])};
  glm::vec3 g[4];
  const float volume = sim::tetrahedron_volume(x, g);
  float rate = 0.0f;
  if (thin) {
    for (int i = 0; i < 4; ++i)
      rate += glm::dot(g[i], glm::vec3(velocity[i]));
  }
  const float reached = volume + h * glm::min(rate, 0.0f);
  const float watch = kVolumeWatch * pair.thickness;
  return reached < watch;
}

/// How deep below its thickness a contact may still be after a projection's iterations before
/// more are due (contact_violated), as a share of the thickness.
inline constexpr float kResidualShare = 0.5f;
/// A projection runs at most this many times the iterations asked for.
inline constexpr int kMaxIterationFactor = 4;

/// Whether an active constraint is still violated by more than kResidualShare of its
/// thickness after a projection's iterations (C < -share x thickness; a volume constraint's
/// tetrahedron below share x its floor): the sweeps have not converged there, and another
/// iteration is due. With the Jacobi iterations the sweeps replaced, at three times the impact
/// scene's speed with self-contact on, the bodies went through each other at their first
/// contact after 8 iterations (and after 16) but not after 12, 24 or 32
/// (docs/notes/2026-12-05-self-contact-cost.md). A sliver tetrahedron under two surface faces
/// of the lion (a hundredth of its tetrahedra's mean volume) turned inside out within the
/// iterations asked and took one face through the other: the impact's self-intersecting frames
/// with self-contact and the floor on (docs/notes/2026-12-06-slivers-and-hold-depth.md). Only
/// constraints flagged `converge` count: the host leaves it 0 between bodies that the frame's
/// exact pass found intersecting, which are taken apart over substeps (iterating on their deep
/// constraints until they were out took half_overlap's bodies through each other), and for
/// untangling constraints (one moves at most max_untangle_step an iteration by design).
inline bool contact_violated(const gpu::ContactPair& pair, const glm::vec4 position[4],
                             const glm::vec3 start[4]) {
  if (!(pair.converge > 0.0f)) return false;
  const glm::vec3 x[4] = {glm::vec3(position[0]), glm::vec3(position[1]), glm::vec3(position[2]),
                          glm::vec3(position[3])};
  if (pair.kind == gpu::kContactVolume) {
    glm::vec3 g[4];
    return sim::tetrahedron_volume(x, g) < kResidualShare * pair.thickness;
  }
  glm::vec3 n(0.0f);
  float b[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  float c = 0.0f;
  return contact_geometry(pair, x, start, n, b, c) && c < -kResidualShare * pair.thickness;
}

/// The solve pass of a volume constraint (kContactVolume), called by solve_contact: the
/// tetrahedron's collapse rate (the volume's, sum of g_k . v_k) is cancelled beyond the rate
/// that would bring it to its floor in one substep (speculative: above the floor, where it
/// is watched from (kVolumeWatch), it holds nothing slower), moving the nodes
/// by that change x h, and the volume left below the floor (pair.thickness) is restored by
/// position alone, along the gradient g, node k weighing its inverse mass w_k (the sweep's
/// next constraint sees the move: no mass splitting): node k moves w_k g_k lambda, which
/// conserves momentum (the gradients sum to zero). given[0] x and y carry the rate and the volume
/// given over the substep's iterations, corrected each iteration and never below zero, as
/// solve_contact's normal totals. No node moves more than pair.step_limit in one iteration: a
/// tetrahedron flattened to a line has gradients near zero, and 1 / their square would throw its
/// nodes.
///
/// Why (issue 33): edge springs hold a mirrored tetrahedron at rest lengths, and the linear
/// volume force alone, explicit, does not stop a node carried through the opposite face in one
/// substep. Inverted tetrahedra fold the surface through itself, where no surface constraint
/// can undo the fold: on the impact with self-contact (60 frames), up to 3,841 of 26,152 were
/// inverted at once and 591 surface triangle pairs intersected; with a floor of 0.3 x the rest
/// volume, at most 18 and 6 (docs/notes/2026-12-05-volume-floor.md).
inline void solve_volume(const gpu::ContactPair& pair, const glm::vec4 position[4],
                         const glm::vec4 velocity[4], const ContactConstants& k, glm::vec4 given[3],
                         glm::vec4 correction[8]) {
  const glm::vec3 x[4] = {glm::vec3(position[0]), glm::vec3(position[1]), glm::vec3(position[2]),
                          glm::vec3(position[3])};
  glm::vec3 g[4];
  const float volume = sim::tetrahedron_volume(x, g);
  float weight = 0.0f;
  float rate = 0.0f;
  float lever = 0.0f;  // the largest w_k |g_k|: node k moves w_k |g_k| |lambda|
  for (int i = 0; i < 4; ++i) {
    const float g2 = glm::dot(g[i], g[i]);
    weight += position[i].w * g2;
    rate += glm::dot(g[i], glm::vec3(velocity[i]));
    lever = glm::max(lever, position[i].w * std::sqrt(g2));
  }
  if (!(weight > 0.0f)) return;  // every node fixed, or a tetrahedron collapsed to a point
  const float room = glm::max(volume - pair.thickness, 0.0f) / k.h;  // the collapse rate allowed
  float speed = glm::max(given[0].x - rate - room, 0.0f) - given[0].x;
  float push = glm::max(given[0].y - ((volume - pair.thickness) + speed * k.h), 0.0f) - given[0].y;
  const float move = lever * std::abs(speed * k.h + push) / weight;
  if (move > pair.step_limit) {
    const float scale = pair.step_limit / move;
    speed *= scale;
    push *= scale;
  }
  given[0].x += speed;
  given[0].y += push;
  for (int i = 0; i < 4; ++i) {
    const float share = position[i].w / weight;
    const glm::vec3 dv = (share * speed) * g[i];
    const glm::vec3 dx = dv * k.h + (share * push) * g[i];
    correction[2 * i] = glm::vec4(dx, 0.0f);
    correction[2 * i + 1] = glm::vec4(dv, 0.0f);
  }
}

/// The solve: one active constraint's corrections of its four nodes into correction[2 k]
/// (position change) and correction[2 k + 1] (velocity change), from the current positions
/// (w = inverse mass), velocities and, for a contact, the nodes' counts of active contacts
/// (mass splitting: node k weighs as if its inverse mass were count[k] x w; a volume
/// constraint reads no count). The sweep applies them at once (apply_correction). Along the normal,
/// the approach velocity is cancelled (and restitution x the first iteration's approach given
/// back), which also moves the nodes by that velocity change x h; depth left after that is removed
/// by position alone, without adding velocity (so a deep start or a tunnel does not turn into a
/// launch), an untangling constraint by at most max_untangle_step per iteration. Tangentially,
/// Coulomb friction on the relative velocity: the substep's friction total (a vector) stays within
/// friction_static x the accumulated normal velocity change, or within friction_dynamic x it
/// where the contact slides (`last_iteration`). All along the weights,
/// so momentum is conserved; a node moves at most its share of the whole correction (see
/// `reduce`).
///
/// `history`: how many of its free nodes slid in the last substep (slid_before); the contact
/// slid through it (`was_sliding`) where all did. In the last iteration the w of each corner's
/// velocity correction is 1 where it slides on (the backend stamps its free nodes after the
/// sweep, for the next substep), else 0. `start`: the nodes' projection starts (projection_start),
/// from which a sticking contact's hold measures how far pushes carried its point; `window_start`:
/// where they started the window (contact_geometry's `start`).
///
/// `given` (three ContactImpulse slots, 3 a to 3 a + 2, per acting constraint) carries what the
/// constraint has given over the substep's iterations so far: given[0] x the normal speed, y the
/// push, z the first iteration's approach; given[1] xyz the friction (a velocity, in the units
/// of given[0].x), w the first iteration's slip; given[2] xyz the hold (a position), w 1 where
/// the first iteration's friction left the static cone; the first iteration resets them. Each
/// iteration corrects the totals (the normal ones never below zero, the friction within its
/// cone, as sequential impulses clamp theirs): a constraint that an earlier iteration
/// over-corrected, because its nodes' other constraints then moved them too, takes the excess
/// back instead of leaving it. Without that, a light node on an edge whose heavier end another
/// constraint also stops was thrown off the surface every substep (the rigid-lever correction of
/// the edge-edge constraint, never undone once the contact point separated), the main source of the
/// stack scene's resting jitter.
inline void solve_contact(const gpu::ContactPair& pair, const glm::vec4 position[4],
                          const glm::vec4 velocity[4], const std::uint32_t count[4],
                          const glm::vec4 start[4], const glm::vec3 window_start[4],
                          const ContactConstants& k, bool first_iteration, bool last_iteration,
                          std::uint32_t history, glm::vec4 given[3], glm::vec4 correction[8]) {
  for (int i = 0; i < 8; ++i)
    correction[i] = glm::vec4(0.0f);
  if (first_iteration) given[0] = given[1] = given[2] = glm::vec4(0.0f);
  if (pair.kind == gpu::kContactVolume) {
    solve_volume(pair, position, velocity, k, given, correction);
    return;
  }
  const glm::vec3 x[4] = {glm::vec3(position[0]), glm::vec3(position[1]), glm::vec3(position[2]),
                          glm::vec3(position[3])};
  glm::vec3 n(0.0f);
  float b[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  float c = 0.0f;
  if (!contact_geometry(pair, x, window_start, n, b, c)) return;
  float weight = 0.0f;
  glm::vec3 relative_velocity(0.0f);
  glm::vec3 drift(0.0f);  // how far position corrections carried the contact point
  for (int i = 0; i < 4; ++i) {
    weight += static_cast<float>(count[i]) * position[i].w * b[i] * b[i];
    relative_velocity += b[i] * glm::vec3(velocity[i]);
    drift += b[i] * ((x[i] - k.h * glm::vec3(velocity[i])) - glm::vec3(start[i]));
  }
  if (!(weight > 0.0f)) return;  // every node fixed
  // No node moves more than 10 x its share (1 / its count) of the whole correction: a node
  // with little leverage on the contact point (a small barycentric weight) whose partners are
  // fixed or much heavier would otherwise be thrown by 1 / that weight x it (hundreds of metres
  // in one projection at the folding plate's fixed hinge, and the springs then blew up). Every
  // part of the correction is scaled down alike, so that momentum stays conserved. A tighter
  // bound weakens ordinary contacts: at 4 x the impact scene intersects in 1 frame of 120, at
  // 2 x in 22.
  float reduce = 1.0f;
  for (int i = 0; i < 4; ++i) {
    const float lever = static_cast<float>(count[i]) * position[i].w * std::abs(b[i]);
    if (lever > 10.0f * weight) reduce = std::min(reduce, 10.0f * weight / lever);
  }
  const float normal_velocity = glm::dot(relative_velocity, n);
  if (first_iteration) given[0].z = glm::max(-normal_velocity, 0.0f);
  const float total_speed =
      glm::max(given[0].x + (k.restitution * given[0].z - normal_velocity) * reduce, 0.0f);
  const float normal_speed = total_speed - given[0].x;
  given[0].x = total_speed;
  float total_push = glm::max(given[0].y - (c + normal_speed * k.h) * reduce, 0.0f);
  if (pair.kind == gpu::kContactUntangle)
    total_push = glm::min(total_push, given[0].y + k.max_untangle_step);
  const float push = total_push - given[0].y;
  given[0].y = total_push;
  // Coulomb friction as a vector total over the substep's iterations (given[1].xyz, a speed like
  // given[0].x), clamped at every iteration to the cone of the accumulated normal change
  // (given[0].x), as sequential impulses clamp theirs: the total wanted is what was given (in
  // the current tangent plane) plus what stops the slip left now. The total may shrink or turn, so
  // friction an iteration over-corrected (its neighbours stopped the same slip), or that a
  // normal total later iterations took back no longer bounds, is given back. The scalar sum of
  // each iteration's magnitude this replaces spent both against the bound: a block held on 28
  // degrees used 0.62 x its normal change in friction for 0.535 x of net friction, and a block
  // sliding with dynamic 0.45 got 0.479 x (0.93 m in 2 s against Coulomb's 1.415 m;
  // docs/notes/2026-12-04-friction.md).
  //
  // Sticking or sliding is a state, as Coulomb's law has it: a contact that slid through the
  // last substep (`was_sliding`, slid_before) has friction_dynamic's cone from its first
  // iteration, and slides on while its first iteration's slip is more than friction_static's
  // cone could have stopped (it sticks again once its points have all but stopped). A sticking
  // contact has friction_static's cone until the last iteration; there it starts sliding
  // (friction_dynamic's cone) only if its first iteration's wanted friction left
  // friction_static's cone (Coulomb's test, taken where every contact of a node sees the whole
  // slip with its share of the load, before the sweep has moved the slip from one to the next)
  // and half or more of that iteration's slip is left: a constraint whose cone its share of a
  // node's slip overflows, while the node's other constraints stop the node, does not slide, its
  // point does not move. Judged by its own cone in the last iteration (slide when the wanted
  // total leaves friction_static's), an elastic block on 28 degrees with 0.7 / 0.45 slid at the
  // dynamic cone's net friction within 4 frames of the tilt, though held it needs 0.53; in a
  // sweep, so did it by the half-slip condition alone (1.48 m in 2 s: the contacts later in the
  // sweep see little slip first; docs/notes/2026-12-07-gauss-seidel-probe.md). Without the state
  // (the choice made afresh each substep), a slow slip was stopped by the static cone in the
  // iterations before each last one: a block tilted gradually past its static angle broke away late
  // and slid 10-21 % short of Coulomb's distance (docs/notes/2026-12-05-friction-tilt.md). The
  // slide flag of the last iteration (1 in the w of each corner's velocity slot) is what the
  // backend stamps after the sweep.
  const glm::vec3 tangential = relative_velocity - normal_velocity * n;
  const glm::vec3 before = glm::vec3(given[1]);
  const glm::vec3 held = before - glm::dot(before, n) * n;  // in the tangent plane of now
  const glm::vec3 wanted = held - reduce * tangential;      // the total that stops the slip
  const float wanted_length = std::sqrt(glm::dot(wanted, wanted));
  const float slip_left = reduce * std::sqrt(glm::dot(tangential, tangential));
  if (first_iteration) given[1].w = slip_left;
  float overflowed = given[2].w;  // 1: the first iteration's friction left the static cone
  if (first_iteration) overflowed = wanted_length > k.friction_static * given[0].x ? 1.0f : 0.0f;
  const bool was_sliding = history == kAllSlid;
  const bool starts_sliding =
      !was_sliding && last_iteration && overflowed > 0.0f && slip_left > 0.5f * given[1].w;
  const bool dynamic = was_sliding || starts_sliding;
  const float limit = (dynamic ? k.friction_dynamic : k.friction_static) * given[0].x;
  glm::vec3 friction_total = wanted;
  if (wanted_length > limit) friction_total = wanted * (limit / wanted_length);
  const bool slides =
      starts_sliding || (was_sliding && given[1].w > k.friction_static * given[0].x);
  given[1] = glm::vec4(friction_total, given[1].w);
  const glm::vec3 friction = friction_total - held;
  // Static friction holds positions too (the hold, given[2].xyz): a sticking contact none of
  // whose free nodes slid in the last substep (history, slid_before) takes back the tangential
  // drift of its point that position corrections made in this projection (the velocity
  // friction above sees only velocities), within friction_static's cone of the push (a
  // position correction bounded by the normal position correction, as the friction is by the
  // normal speed). A sliding contact holds nothing. Why: the volume floor's pushes move the
  // nodes of a resting body along the tetrahedra's gradients without a velocity, and the stack
  // with the floor crept at 2-8 mm/s and never slept; with the hold it sleeps
  // (docs/notes/2026-12-05-hold.md).
  const glm::vec3 drift_tangential = drift - glm::dot(drift, n) * n;
  const glm::vec3 before_hold = glm::vec3(given[2]);
  const glm::vec3 held_hold = before_hold - glm::dot(before_hold, n) * n;
  glm::vec3 hold_total(0.0f);
  if (!dynamic && history == kNoneSlid) {
    const glm::vec3 wanted_hold = held_hold - reduce * drift_tangential;
    const float wanted_hold_length = std::sqrt(glm::dot(wanted_hold, wanted_hold));
    const float hold_limit = k.friction_static * given[0].y;
    hold_total = wanted_hold;
    if (wanted_hold_length > hold_limit)
      hold_total = wanted_hold * (hold_limit / wanted_hold_length);
  }
  given[2] = glm::vec4(hold_total, overflowed);
  const glm::vec3 hold = hold_total - held_hold;
  const glm::vec3 dv = (normal_speed * n + friction) / weight;
  const glm::vec3 dx = dv * k.h + (push / weight) * n + hold / weight;
  const float slide_flag = last_iteration && slides ? 1.0f : 0.0f;
  for (int i = 0; i < 4; ++i) {
    const float scale = position[i].w * b[i];
    correction[2 * i] = glm::vec4(scale * dx, 0.0f);
    correction[2 * i + 1] = glm::vec4(scale * dv, slide_flag);
  }
}

/// Applies a node's corrections to its position and velocity. Fixed nodes (inverse mass 0)
/// are left alone (their motion is prescribed).
inline void apply_correction(glm::vec4& position, glm::vec4& velocity, const glm::vec3& dx,
                             const glm::vec3& dv) {
  if (!(position.w > 0.0f)) return;
  const glm::vec3 p = glm::vec3(position) + dx;
  velocity = glm::vec4(glm::vec3(velocity) + dv, 0.0f);
  position = glm::vec4(p, position.w);
}

/// Whether a free node at `position`, `deviation` from its straight path (path_deviation), has
/// strayed beyond its reach (frame_start.w): beyond the motion the window's proximity search
/// assumed, so that the search must run again. Fixed nodes never stray (their motion is
/// prescribed).
inline bool beyond_reach(float deviation, const glm::vec4& position, const glm::vec4& frame_start) {
  return position.w > 0.0f && deviation > frame_start.w;
}

/// beyond_reach of a node at `position`: its deviation from where the window's start
/// (frame_start.xyz) carried along its path (node_motion.xyz x elapsed) puts it.
inline bool strayed(const glm::vec4& position, const glm::vec4& frame_start,
                    const glm::vec4& node_motion, float elapsed) {
  return beyond_reach(path_deviation(glm::vec3(position), frame_start, node_motion, elapsed),
                      position, frame_start);
}

}  // namespace deformcd::response
