#include "deformcd/render/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "deformcd/error.h"

namespace deformcd::render {

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// The unit vector from the target to the eye.
glm::vec3 eye_direction(float yaw_degrees, float pitch_degrees) {
  const float yaw = glm::radians(yaw_degrees);
  const float pitch = glm::radians(pitch_degrees);
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}

}  // namespace

glm::vec3 Camera::eye() const {
  return target + distance * eye_direction(yaw_degrees, pitch_degrees);
}

glm::mat4 Camera::view() const {
  return glm::lookAt(eye(), target, kUp);
}

glm::mat4 Camera::projection(float aspect) const {
  // Near and far scale with the distance: bodies around the target stay between them whatever
  // the zoom, and the 1:10^4 ratio keeps a 24-bit depth buffer precise enough.
  return glm::perspective(glm::radians(fov_y_degrees), aspect, 0.01f * distance, 100.0f * distance);
}

glm::mat4 Camera::view_projection(float aspect) const {
  return projection(aspect) * view();
}

void Camera::orbit(float yaw_delta_degrees, float pitch_delta_degrees) {
  yaw_degrees = std::fmod(yaw_degrees + yaw_delta_degrees, 360.0f);
  // At +-90 degrees the view direction is parallel to the up vector and lookAt degenerates.
  pitch_degrees = std::clamp(pitch_degrees + pitch_delta_degrees, -89.0f, 89.0f);
}

void Camera::zoom(float factor) {
  if (!(factor > 0.0f) || !std::isfinite(factor)) return;
  distance = std::clamp(distance * factor, 1e-4f, 1e6f);
}

void Camera::pan(float dx, float dy) {
  const glm::vec3 forward = -eye_direction(yaw_degrees, pitch_degrees);
  const glm::vec3 right = glm::normalize(glm::cross(forward, kUp));
  const glm::vec3 up = glm::cross(right, forward);
  const float view_height = 2.0f * distance * std::tan(glm::radians(fov_y_degrees) / 2.0f);
  target += view_height * (dx * right + dy * up);
}

Camera Camera::framing(const Bounds& bounds, float aspect, FramingView view) {
  if (!(aspect > 0.0f) || !std::isfinite(aspect)) {
    throw Error("Camera::framing: the aspect ratio must be positive and finite");
  }
  Camera camera;
  camera.target = glm::vec3((bounds.min + bounds.max) / 2.0);
  if (view == FramingView::kThreeQuarter) {
    camera.yaw_degrees = 35.0f;
    camera.pitch_degrees = 25.0f;
  } else {
    camera.yaw_degrees = 0.0f;
    camera.pitch_degrees = 12.0f;
  }
  const glm::vec3 to_eye = eye_direction(camera.yaw_degrees, camera.pitch_degrees);
  const glm::vec3 right = glm::normalize(glm::cross(-to_eye, kUp));
  const glm::vec3 up = glm::cross(right, -to_eye);
  // Fit into 90 % of the view: a corner at (x, y, z) in camera axes about the target (z towards
  // the eye) is in view when |x| <= (distance - z) tan(half fov x), and likewise for y.
  const float margin = 0.9f;
  const float tan_y = margin * std::tan(glm::radians(camera.fov_y_degrees) / 2.0f);
  const float tan_x = tan_y * aspect;
  float distance = std::numeric_limits<float>::min();
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? bounds.max.x : bounds.min.x,
                       (corner & 2) ? bounds.max.y : bounds.min.y,
                       (corner & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec3 offset = glm::vec3(p) - camera.target;
    const float z = glm::dot(offset, to_eye);
    distance = std::max({distance, z + std::abs(glm::dot(offset, right)) / tan_x,
                         z + std::abs(glm::dot(offset, up)) / tan_y});
  }
  if (!std::isfinite(distance)) throw Error("Camera::framing: the bounds are not finite");
  // An empty or flat box still gets a usable distance.
  camera.distance = std::max(distance, 1e-3f);
  return camera;
}

Bounds swept_bounds(const std::vector<BodyInit>& bodies, float seconds) {
  Bounds all{glm::dvec3(std::numeric_limits<double>::max()),
             glm::dvec3(std::numeric_limits<double>::lowest())};
  for (const BodyInit& init : bodies) {
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(std::numeric_limits<double>::lowest());
    for (const glm::vec4& p : init.body.positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
    if (init.body.positions.empty()) continue;
    const glm::dvec3 grow(0.05 * glm::length(hi - lo));
    const glm::dvec3 travel = glm::dvec3(init.carry_velocity) * static_cast<double>(seconds);
    all.min = glm::min(all.min, glm::min(lo, lo + travel) - grow);
    all.max = glm::max(all.max, glm::max(hi, hi + travel) + grow);
  }
  if (all.min.x > all.max.x) throw Error("swept_bounds: no body has any node");
  return all;
}

}  // namespace deformcd::render
