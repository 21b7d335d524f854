#pragma once
// Each body's self-contact pairs kept from one search to the next while the body moves as a
// whole (issue 33), after Offset Geometric Contact's per-vertex conservative bounds (Chen,
// Hsu, Liu, Macklin, Yang, Yuksel 2025).
//
// A search of a body against itself on its positions P (the references), with a reach of half
// its thickness plus a margin d per vertex and no motion, finds every pair of its surface within
// the thickness + 2 d there. A pair's distance changes by at most the most any of its vertices
// moves, and a rigid motion of the whole body changes none: so while one rigid map G (any,
// chosen afresh at each moment) takes every surface vertex to within d of its reference,
// |G(x_i) - P_i| <= d, those pairs hold every pair of the surface within the thickness. G is the
// best rigid fit of the surface to its references (the polar decomposition of their covariance),
// and the bound is checked on the positions of every projection (holds()).
//
// At each search window's start a body is planned by its drift from its references (under that
// fit) and by how fast it deforms (its velocities apart from the best rigid fit of a translation
// and a rotation to them, over the window): a body expected to stay within d keeps its pairs;
// one that has drifted or turned but deforms slowly is searched against itself again on the
// positions now; one that deforms fast (an impact, a fold) has its pairs with itself found by
// the window's search, swept along each vertex's path as the pairs between bodies are. A body
// falling, thrown, spinning or at rest is searched against itself once, not once a window.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/detector.h"
#include "deformcd/gpu_layout.h"

namespace deformcd {

class SelfContact {
 public:
  /// The margin d, in the body's thickness: a larger one finds more pairs in a search (within
  /// thickness + 2 d) and keeps them longer.
  static constexpr float kMargin = 0.5f;

  /// Every body searched against itself: `objects` where each body's nodes start; `on_surface`
  /// per node; `thickness` per body (m).
  SelfContact(const std::vector<gpu::ObjectInfo>& objects,
              const std::vector<std::uint8_t>& on_surface, std::vector<float> thickness);

  /// Per body, for a window starting at node positions `x`, the nodes at velocities
  /// node_motion.xyz (m/s), `window` seconds long: `kept`, its pairs are expected to hold
  /// through the window (holds() checks it at every projection); `search`, it is to be searched
  /// against itself now (then take()); neither: its pairs with itself are the window's
  /// search's. Bodies that cannot move (`movable` 0) are neither.
  struct Plan {
    std::vector<std::uint8_t> kept;
    std::vector<std::uint8_t> search;
  };
  [[nodiscard]] Plan plan(const std::vector<glm::vec3>& x,
                          const std::vector<glm::vec4>& node_motion, float window,
                          const std::vector<std::uint8_t>& movable);
  /// The per-vertex reach of a search of bodies against themselves (every node: its body's
  /// half thickness + d).
  [[nodiscard]] std::vector<float> search_reach() const;
  /// Takes the pairs that a search with search_reach() found on positions `x` for the bodies
  /// flagged in `searched` (pairs of other bodies are ignored): those are their references now.
  void take(const std::vector<ProximityPair>& found, const std::vector<glm::vec3>& x,
            const std::vector<std::uint8_t>& searched);
  /// Whether body b's pairs hold from positions `x` through the next `h` seconds at velocities
  /// `v` (xyz read): the best rigid fit takes every surface vertex to within d of its
  /// reference, less what it deforms over h.
  [[nodiscard]] bool holds(std::uint32_t body, std::span<const glm::vec4> x,
                           std::span<const glm::vec4> v, float h);

  /// Body b's pairs (indices local to the body), their distance on the references.
  [[nodiscard]] const std::vector<ProximityPair>& pairs(std::uint32_t body) const {
    return pairs_[body];
  }

 private:
  /// The most any surface vertex of body b at positions x is from its reference under the best
  /// rigid fit (X indexes glm::vec3 or glm::vec4 per node: xyz read).
  template <class X>
  [[nodiscard]] double drift(std::uint32_t body, const X& x);
  /// The most any surface vertex of body b at positions x, velocities node_motion.xyz, moves
  /// apart from the body's rigid motion over `window` seconds (infinity when the body turns by
  /// more than half a radian).
  template <class X>
  [[nodiscard]] double deformation(std::uint32_t body, const X& x,
                                   std::span<const glm::vec4> node_motion, float window) const;

  /// Whether body b has been searched against itself (a body without surface needs no search).
  [[nodiscard]] bool has_references(std::uint32_t body) const {
    return !reference_[body].empty() || surface_[body].empty();
  }

  std::vector<gpu::ObjectInfo> objects_;
  std::vector<float> thickness_;                     // per body
  std::vector<std::vector<std::uint32_t>> surface_;  // per body: its surface nodes (global)
  std::vector<std::vector<glm::vec3>> reference_;    // per body, per surface node: P_i
  std::vector<glm::dquat> rotation_;                 // per body: the last fit's (a warm start)
  std::vector<std::vector<ProximityPair>> pairs_;    // per body
};

}  // namespace deformcd
