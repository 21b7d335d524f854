#pragma once
/// \file response.h
/// Contact response settings: bodies that touch push each other apart instead of passing
/// through (WorldOptions::response, a scene's `response` object).
///
/// Each frame the world finds the vertex-triangle and edge-edge pairs of its bodies (and of one
/// body with itself, with self-collision) that may come closer than the contact thickness
/// during the frame (Detector::find_proximity, with a bound on each body's motion); after every
/// substep it projects them apart (position-based, Gauss-Seidel sweeps, momentum-conserving), with
/// Coulomb friction. Surfaces that already intersect (a start pose that overlaps, a frame fast
/// enough to tunnel) are pushed apart along the exact intersection the detector found, each vertex
/// out of the other body through the face it crosses.

#include <optional>

namespace deformcd {

/// The most a frame's substeps may grow over the scene's by ResponseSettings::substep_motion.
inline constexpr int kMaxSubstepFactor = 8;

/// Whether bodies collide with themselves, given the setting (WorldOptions::self_collision, a
/// scene's `collision.self`) and whether there is a contact response: unset, on exactly with a
/// response, since a response without it lets a soft body fold through itself where another
/// presses it.
[[nodiscard]] inline bool self_collision_on(std::optional<bool> self, bool responds) {
  return self.value_or(responds);
}

/// A scene body's node mass floor (BodyOptions::node_mass_floor) when its `material` sets none
/// and the scene has a contact response. Pure lumping leaves surface nodes thousands of times
/// lighter than interior ones, and a contact and a volume floor on such a node move mostly it,
/// back and forth, to the iteration cap: at 0.3 the impact and the stack take a quarter to a
/// third fewer iterations a frame, the pile sleeps 34 frames sooner, and the 26 perturbed impact
/// starts hold (docs/simulation-and-response.md, "Node masses").
inline constexpr double kResponseNodeMassFloor = 0.3;

/// A body's node mass floor, given its setting (a scene's `material.node_mass_floor`) and
/// whether there is a contact response: unset, kResponseNodeMassFloor with a response, else 0
/// (pure lumping).
[[nodiscard]] inline double node_mass_floor_on(std::optional<double> floor, bool responds) {
  return floor.value_or(responds ? kResponseNodeMassFloor : 0.0);
}

/// The most sweeps per substep ResponseSettings::iterations may ask for.
inline constexpr int kMaxResponseIterations = 64;

/// Sleeping (ResponseSettings::sleep), as rigid-body engines let resting bodies sleep (Box2D's
/// islands, PhysX's sleep threshold): bodies linked by contact constraints form an island; when
/// every body of an island has moved slowly for `time` seconds, the island falls asleep: its
/// nodes hold still (velocity 0, and to the contact response they are fixed, immovable
/// obstacles) until a body that is not asleep comes into contact with one of them, which wakes
/// the whole island. Bodies with fixed nodes only (a base) join no island and bodies carried
/// along a path never sleep. A body is slow in a frame when the mass-weighted root mean square
/// of its nodes' moves over the frame stays below `speed` x its mean surface edge length per
/// second x the frame's length (the motion a viewer sees: velocities that cancel within the
/// frame, where constraints fight at rest, do not keep a body awake), and, with the volume
/// floor on, none of its tetrahedra is inside out (asleep, it would keep the fold until woken).
struct SleepSettings {
  /// Mean surface edges per second (> 0).
  float speed = 0.5f;
  /// s (> 0): how long an island's bodies must all be slow before it sleeps.
  float time = 0.25f;
};

/// Contact response parameters (a scene's `response` object; docs/simulation-and-response.md).
struct ResponseSettings {
  /// m: the gap contacts keep between surfaces, for every body. Unset: each body's
  /// relative_thickness x its mean surface edge length; two bodies keep the thinner one's.
  std::optional<float> thickness;
  /// The thickness over the body's mean surface edge length, when thickness is unset.
  float relative_thickness = 0.2f;
  /// Coulomb friction: a contact's friction over a substep (all its projections together) is
  /// at most friction_static x the normal velocity change it gave in that substep while it
  /// sticks, and friction_dynamic x that change when its slip goes on (half or more of the
  /// substep's first slip is left after the projections).
  float friction_static = 0.4f;
  float friction_dynamic = 0.3f;  ///< at most friction_static
  /// 0: the approach speed is absorbed at contact (the bodies' elasticity still makes them
  /// rebound); 1: it is given back.
  float restitution = 0.0f;
  /// Most the untangling constraints move their nodes per substep (all iterations together; up
  /// to 4 x in a substep whose projection iterates on, see `iterations`), relative to the
  /// smallest body's mean surface edge length. Small values separate
  /// overlapped bodies gently but slowly, and the elastic bodies then push part of the way back
  /// between substeps: on the overlap scene 0.02 lets the intersection contour grow back by a
  /// quarter on its way to zero, 0.25 shrinks it every frame.
  float untangle_step = 0.25f;
  /// Each tetrahedron of a moving body is kept at or above this fraction of its rest volume
  /// (0 turns it off; below 1): a constraint of the projection, solved after the contacts in
  /// each iteration (and iterated on while a tetrahedron is below half its floor, as a contact
  /// deeper than half its thickness is), that takes back the motion collapsing it and pushes
  /// its corners out along its volume's gradient. Inverted tetrahedra fold a body's surface through
  /// itself, where no contact between surfaces can undo the fold: on the impact with self-contact,
  /// 0.3 takes the most self-intersecting triangle pairs in a frame from 591 to 6 and the most
  /// inverted tetrahedra from 3,841 to 18 (docs/simulation-and-response.md, "Volume
  /// constraints"). Alone it makes the impact's frames in contact about a third dearer.
  float volume_floor = 0.3f;
  /// Motion-bounded substeps (0 turns them off): when > 0, a frame takes more substeps than the
  /// scene's `substeps` where the pairs its first search finds could close on each other (each
  /// pair's closing speed, the bound its nodes' straight paths give) by more than this many
  /// contact thicknesses (the smallest body's) in one substep; at most kMaxSubstepFactor x the
  /// scene's count. A fast approach then never crosses the thickness,
  /// inside which the projection holds it, in one substep. On the impact at three times its
  /// speed with self-contact and volume_floor 0.3, 0.3 keeps the bodies apart where 16 fixed
  /// substeps let them into each other (docs/simulation-and-response.md, "Motion-bounded
  /// substeps").
  float substep_motion = 0.3f;
  /// Iterations per substep (1 to 64): Gauss-Seidel sweeps over the constraints that act in
  /// the substep, each solved on the positions the ones before it left, correcting what it has
  /// given so far (a total that never goes below zero, so an over-correction is taken back).
  /// On the impact scene the sweeps converge within 8
  /// (docs/notes/2026-12-07-gauss-seidel-probe.md); resting bodies jitter less with more, at a cost
  /// that grows with them. A projection runs more, up to 4 x these, while an active contact is
  /// still deeper than half its thickness or a tetrahedron below half its volume_floor
  /// (ResponseCounts::iterations counts them).
  int iterations = 8;
  /// Resting islands of bodies fall asleep (see SleepSettings). Unset: bodies never sleep.
  std::optional<SleepSettings> sleep;
};

/// Throws Error naming the field ("friction_static must be >= 0, not -1") when a value is
/// negative or not finite, friction_dynamic exceeds friction_static, restitution exceeds 1,
/// volume_floor is 1 or more, iterations is outside 1 to 64, or a sleep setting is not positive
/// and finite.
void check_response_settings(const ResponseSettings& settings);

}  // namespace deformcd
