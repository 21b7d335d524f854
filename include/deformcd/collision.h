#pragma once
/// \file collision.h
/// What collision detection reports: the broad phases a world can run, and the intersecting
/// surface-face pairs (the contacts) found each frame, between different bodies and, with
/// WorldOptions::self_collision, within one body.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace deformcd {

/// How candidate face pairs are chosen before the exact triangle-triangle test. Every broad
/// phase returns exactly the pairs that kBrute returns.
enum class BroadPhase {
  kNone,    ///< no collision detection
  kBrute,   ///< every face of body A against every face of body B (the paper's baseline)
  kOctree,  ///< the paper's method: 64 leaf boxes per body, box-pair mask, N' x M' face rows
  /// Beyond the paper: the paper's boxes, but the triangle tests run over the compacted face
  /// pairs of overlapping boxes only.
  kOctreeCompact,
  /// Beyond the paper: a BVH per body (one face per leaf), refitted every frame; body pairs
  /// culled by their root boxes; tree traversal appends candidate pairs, tested alone.
  kBvh,
};

/// "none", "brute", "octree", "octree-compact" or "bvh"; throws Error listing the valid names
/// otherwise.
[[nodiscard]] BroadPhase parse_broadphase(std::string_view name);
/// The name parse_broadphase takes.
[[nodiscard]] std::string_view broadphase_name(BroadPhase method);
/// The names of the broad phases that detect collisions (all but "none").
[[nodiscard]] const std::vector<std::string>& broadphase_names();

/// One side of a contact: a surface face of a body.
struct ContactFace {
  std::uint32_t body = 0;                ///< body index in the world
  std::uint32_t face = 0;                ///< face index within the body (Body::faces)
  std::array<std::uint32_t, 3> nodes{};  ///< the face's nodes, indices within the body
};

/// Two intersecting surface faces: of different bodies (a.body < b.body) or, with
/// self-collision, of one body (a.body == b.body, a.face < b.face). Faces of one body that share
/// an edge are never a contact; faces sharing one node are when they also meet elsewhere (then
/// the segment starts or ends at that node).
struct Contact {
  ContactFace a;  ///< the face of the lower-numbered body (or, within one body, the lower face)
  ContactFace b;  ///< the other face
  /// Coplanar faces overlap in an area and have no segment (then both ends are 0).
  bool coplanar = false;
  /// Where the two triangles cross (both ends equal when they touch at a point).
  std::array<glm::vec3, 2> segment{glm::vec3(0.0f), glm::vec3(0.0f)};
};

/// What one collision pass found.
struct CollisionCounts {
  std::uint64_t contacts = 0;         ///< intersecting face pairs
  std::uint64_t box_pairs = 0;        ///< overlapping leaf-box pairs (octree; 0 for brute)
  std::uint64_t colliding_faces = 0;  ///< faces in at least one contact
  /// Face pairs given to the triangle test: N x M for brute (N (N - 1) / 2 for a body with
  /// itself), the first-box-pair rows for the octree methods, the pairs whose own boxes overlap
  /// for bvh.
  std::uint64_t candidates = 0;
};

}  // namespace deformcd
