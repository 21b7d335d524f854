#pragma once
// Sleeping bodies (ResponseSettings::sleep): which bodies of a world are asleep, decided after
// each frame from how far the bodies' nodes moved over it and the contact links between them. It
// decides only; the contact response holds a sleeping body's nodes still through the simulation
// backend.
//
// As Box2D does for rigid bodies, the unit that falls asleep and wakes is an island: the bodies
// linked by the frame's contact constraints, through any chain of them. Bodies whose nodes are
// all fixed (a base) join no island: a stack resting on the floor does not link everything on
// the floor. An island sleeps once each of its bodies has been slow for the settings' time; a
// sleeping body is still (velocity 0), so its slow time runs on. An island with a body that is
// not (a body that comes into contact with a sleeping one) wakes as a whole, and its woken
// bodies count their slow time from zero again. Bodies that fell asleep in one island stay
// one while they sleep, whether or not the frame's constraints still join them: the contact
// response does not look for constraints between bodies that cannot move (the search would
// find the same pairs frame after frame and none could act), so a woken body wakes everything
// that slept with it, as Box2D's sleeping islands do.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "deformcd/gpu_layout.h"
#include "deformcd/response.h"

namespace deformcd {

class BodySleep {
 public:
  /// Per body: where its nodes lie (objects), its mean surface edge (m), and whether it may
  /// sleep at all (false for a body carried along a path). `inverse_mass` per node, as the
  /// bodies were given (0: fixed); `dt` the frame's length (s).
  BodySleep(const SleepSettings& settings, const std::vector<gpu::ObjectInfo>& objects,
            std::vector<float> inverse_mass, const std::vector<float>& mean_edge,
            const std::vector<std::uint8_t>& may_sleep, float dt);

  /// After a frame: `position` per node (the frame's end), `links` the body pairs that the
  /// frame's contact constraints joined (those between two sleeping bodies may be left out:
  /// they are joined by the island they fell asleep in), `inverted` per body 1 where one of its
  /// tetrahedra is inside out at the frame's end (empty: none is). A body is slow in a frame
  /// when its nodes moved less than the slow speed x dt since the last frame's end, as a root
  /// mean square (the first frame, with no last one, is not slow), and none of its tetrahedra
  /// is inside out: asleep, a body holds its shape as it is, and one that fell asleep with a
  /// tetrahedron inside out (a bunny's cap sliver at -0.002 of its rest volume, from the pile's
  /// frame 243 at pure lumping, docs/notes/2026-12-07-thin-tetrahedra-watch.md) would keep it so
  /// until woken, its surface folded where a user sees it. Returns the bodies that fell asleep
  /// or woke, ascending.
  ///
  /// Why the motion over the frame, not the velocities: a body held at rest by constraints
  /// that fight (the volume floor's pushes against the contacts' on a crushed bottom layer)
  /// keeps node velocities of 3-8 x the slow speed that cancel over a substep or two, while the
  /// body moves less than the slow speed; judged by its velocities the stack with the floor
  /// never slept (docs/notes/2026-12-05-friction-tilt.md).
  std::vector<std::uint32_t> end_frame(
      std::span<const glm::vec4> position,
      const std::vector<std::pair<std::uint32_t, std::uint32_t>>& links,
      std::span<const std::uint8_t> inverted = {});

  /// Wakes every sleeping body (their slow time counts from zero again, as a woken island's
  /// does). Returns the bodies that woke, ascending.
  std::vector<std::uint32_t> wake_all();

  [[nodiscard]] bool asleep(std::size_t body) const { return asleep_[body] != 0u; }
  [[nodiscard]] std::size_t asleep_count() const;
  /// Body b's nodes' inverse masses while awake (as given), or zeros while asleep.
  [[nodiscard]] std::vector<float> inverse_masses(std::size_t body) const;

 private:
  /// The mass-weighted root mean square of body b's free nodes' moves from last_position_ to
  /// `position`, over dt (m/s).
  [[nodiscard]] double rms_motion(std::size_t body, std::span<const glm::vec4> position) const;

  SleepSettings settings_;
  std::vector<gpu::ObjectInfo> objects_;
  std::vector<float> inverse_mass_;        // per node, as given
  std::vector<float> slow_speed_;          // per body: m/s below which it is slow
  std::vector<std::uint8_t> may_sleep_;    // per body
  std::vector<std::uint8_t> fixed_;        // per body: every node fixed (joins no island)
  std::vector<std::uint8_t> asleep_;       // per body
  std::vector<std::uint32_t> slept_with_;  // per sleeping body: its island's smallest body
  std::vector<float> slow_time_;           // per body: s it has been slow without a break
  std::vector<glm::vec3> last_position_;   // per node: at the last frame's end (none before)
  float dt_ = 0.0f;
};

}  // namespace deformcd
