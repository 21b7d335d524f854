#pragma once
/// \file camera.h
/// An orbit camera for looking at a world's bodies, and the framing that fits them in view.
///
///     const deformcd::Bounds box = deformcd::render::swept_bounds(bodies, frames * dt);
///     deformcd::render::Camera camera = deformcd::render::Camera::framing(box, 4.0f / 3.0f);
///     glm::mat4 clip_from_world = camera.view_projection(4.0f / 3.0f);

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "deformcd/body.h"
#include "deformcd/simulation_state.h"

namespace deformcd::render {

/// Where the framing looks from.
enum class FramingView {
  /// Along -z with 12 degrees of elevation: the bodies of the paper's scenes, which travel
  /// along x, appear side by side and meet in the middle of the image (as in its Figs. 8-10).
  kFront,
  /// From 35 degrees to the side and 25 degrees above.
  kThreeQuarter,
};

/// Looks at `target` from `distance` away; yaw turns the eye about +y (0: the eye on +z, looking
/// along -z), pitch raises it (positive: looking down). Angles in degrees.
struct Camera {
  glm::vec3 target{0.0f};       ///< the point looked at
  float distance = 5.0f;        ///< from the eye to the target
  float yaw_degrees = 0.0f;     ///< turn of the eye about +y
  float pitch_degrees = 0.0f;   ///< raise of the eye (positive: looking down)
  float fov_y_degrees = 35.0f;  ///< vertical field of view

  /// The eye position.
  [[nodiscard]] glm::vec3 eye() const;
  /// World to view (right-handed, looking along -z).
  [[nodiscard]] glm::mat4 view() const;
  /// Perspective projection for width / height = `aspect`; near and far planes follow the
  /// distance, so zooming never clips the target.
  [[nodiscard]] glm::mat4 projection(float aspect) const;
  /// projection(aspect) * view().
  [[nodiscard]] glm::mat4 view_projection(float aspect) const;

  /// Turns the eye about the target; pitch stays within +-89 degrees.
  void orbit(float yaw_delta_degrees, float pitch_delta_degrees);
  /// Multiplies the distance by `factor` (< 1 moves closer), kept within sane limits.
  void zoom(float factor);
  /// Moves the target in the view plane by fractions of the view's height at the target
  /// (dx to the right, dy up), so that a mouse drag keeps the scene under the cursor.
  void pan(float dx, float dy);

  /// The camera seeing from `view` that fits every corner of `bounds` in a viewport of
  /// width / height = `aspect`, with a small margin.
  [[nodiscard]] static Camera framing(const Bounds& bounds, float aspect,
                                      FramingView view = FramingView::kFront);
};

/// The box every body's surface stays within over `seconds` of a run: each body's box at the
/// start and moved along its path (carry velocity x seconds), grown on every side by 5 % of the
/// body's size for the wobble of its start squash. Computed from the bodies before they enter
/// a world, so a camera framed on it stays fixed for the whole run and nothing leaves the view.
[[nodiscard]] Bounds swept_bounds(const std::vector<BodyInit>& bodies, float seconds);

}  // namespace deformcd::render
