#pragma once
/// \file response.h
/// Contact response settings: bodies that touch push each other apart instead of passing
/// through (WorldOptions::response, a scene's `response` object).
///
/// Each frame the world finds the vertex-triangle and edge-edge pairs of its bodies (and of one
/// body with itself, with self-collision) that may come closer than the contact thickness
/// during the frame (Detector::find_proximity, with a bound on each body's motion); after every
/// substep it projects them apart (position-based, Jacobi, momentum-conserving), with Coulomb
/// friction. Surfaces that already intersect (a start pose that overlaps, a frame fast enough to
/// tunnel) are pushed apart along the exact intersection the detector found, each vertex out
/// of the other body through the face it crosses.

#include <optional>

namespace deformcd {

struct ResponseSettings {
  /// m: the gap contacts keep between surfaces, for every body. Unset: each body's
  /// relative_thickness x its mean surface edge length; two bodies keep the mean of theirs.
  std::optional<float> thickness;
  float relative_thickness = 0.2f;
  /// Coulomb friction: sliding starts when the tangential velocity exceeds friction_static x
  /// the normal velocity change of the contact, and is then slowed by friction_dynamic x it.
  float friction_static = 0.4f;
  float friction_dynamic = 0.3f;
  /// 0: the approach speed is absorbed at contact (the bodies' elasticity still makes them
  /// rebound); 1: it is given back.
  float restitution = 0.0f;
  /// Most an untangling constraint moves its nodes per substep, relative to the body's mean
  /// surface edge length: small values separate overlapped bodies gently.
  float untangle_step = 0.02f;
};

/// Throws Error naming the field ("friction_static must be >= 0, not -1") when a value is
/// negative or not finite, friction_dynamic exceeds friction_static, or restitution exceeds 1.
void check_response_settings(const ResponseSettings& settings);

}  // namespace deformcd
