// The orbit camera and the framing that keeps every body in view (no GL needed).

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vec4.hpp>

#include "deformcd/error.h"
#include "deformcd/render/camera.h"
#include "support/mesh_fixtures.h"

namespace deformcd::render {
namespace {

// Normalized device coordinates of `p` seen by `camera`.
glm::vec3 ndc(const Camera& camera, float aspect, const glm::vec3& p) {
  const glm::vec4 clip = camera.view_projection(aspect) * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}

glm::vec3 corner(const Bounds& b, int i) {
  return glm::vec3((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                   (i & 4) ? b.max.z : b.min.z);
}

TEST(Camera, FramingKeepsEveryCornerInViewAndFillsIt) {
  // A wide, shallow box like the paper's scenes (bodies travelling along x).
  const Bounds box{{-1.9, -0.6, -0.5}, {1.9, 0.6, 0.5}};
  for (FramingView view : {FramingView::kFront, FramingView::kThreeQuarter}) {
    for (float aspect : {0.5f, 1.0f, 16.0f / 9.0f, 3.0f}) {
      const Camera camera = Camera::framing(box, aspect, view);
      float widest = 0.0f;
      for (int i = 0; i < 8; ++i) {
        const glm::vec3 p = ndc(camera, aspect, corner(box, i));
        EXPECT_LE(std::abs(p.x), 0.91f) << "aspect " << aspect << " corner " << i;
        EXPECT_LE(std::abs(p.y), 0.91f) << "aspect " << aspect << " corner " << i;
        EXPECT_GT(p.z, -1.0f);  // between the near and far planes
        EXPECT_LT(p.z, 1.0f);
        widest = std::max({widest, std::abs(p.x), std::abs(p.y)});
      }
      // Tight: the outermost corner touches the 90 % margin.
      EXPECT_GT(widest, 0.88f) << "aspect " << aspect;
    }
  }
}

TEST(Camera, FrontViewLooksAlongMinusZFromSlightlyAbove) {
  const Camera camera = Camera::framing({{-1, -1, -1}, {1, 1, 1}}, 1.0f);
  const glm::vec3 to_eye = glm::normalize(camera.eye() - camera.target);
  EXPECT_NEAR(to_eye.x, 0.0f, 1e-6f);
  EXPECT_GT(to_eye.z, 0.9f);
  EXPECT_GT(to_eye.y, 0.1f);
  // +x is to the right of the image, +y up.
  EXPECT_GT(ndc(camera, 1.0f, {1, 0, 0}).x, 0.0f);
  EXPECT_GT(ndc(camera, 1.0f, {0, 1, 0}).y, 0.0f);
}

TEST(Camera, OrbitKeepsTheDistanceAndClampsThePitch) {
  Camera camera;
  camera.target = {1, 2, 3};
  camera.distance = 4.0f;
  camera.orbit(30.0f, 200.0f);
  EXPECT_FLOAT_EQ(camera.pitch_degrees, 89.0f);
  EXPECT_NEAR(glm::length(camera.eye() - camera.target), 4.0f, 1e-5f);
  camera.orbit(0.0f, -400.0f);
  EXPECT_FLOAT_EQ(camera.pitch_degrees, -89.0f);
}

TEST(Camera, ZoomScalesTheDistanceAndIgnoresNonsense) {
  Camera camera;
  camera.distance = 2.0f;
  camera.zoom(0.5f);
  EXPECT_FLOAT_EQ(camera.distance, 1.0f);
  camera.zoom(0.0f);
  camera.zoom(-3.0f);
  camera.zoom(std::nanf(""));
  EXPECT_FLOAT_EQ(camera.distance, 1.0f);
}

TEST(Camera, PanMovesTheTargetAcrossTheView) {
  Camera camera;
  camera.distance = 3.0f;
  const glm::vec3 before = camera.target;
  camera.pan(0.5f, 0.0f);
  // Half the view's height at the target, to the right (+x for the default yaw 0).
  const float height = 2.0f * 3.0f * std::tan(glm::radians(camera.fov_y_degrees) / 2.0f);
  EXPECT_NEAR(camera.target.x - before.x, 0.5f * height, 1e-5f);
  EXPECT_NEAR(camera.target.y, before.y, 1e-6f);
  camera.pan(0.0f, 0.25f);
  EXPECT_NEAR(camera.target.y - before.y, 0.25f * height, 1e-5f);
}

TEST(Camera, FramingRejectsABadAspect) {
  EXPECT_THROW((void)Camera::framing({{0, 0, 0}, {1, 1, 1}}, 0.0f), Error);
  EXPECT_THROW((void)Camera::framing({{0, 0, 0}, {1, 1, 1}}, std::nanf("")), Error);
}

TEST(SweptBounds, CoversTheStartAndEndOfEveryPath) {
  BodyInit a;
  a.body.positions = {glm::vec4(0, 0, 0, 1), glm::vec4(1, 1, 1, 1)};
  a.carry_velocity = {2.0f, 0.0f, 0.0f};
  BodyInit b;
  b.body.positions = {glm::vec4(5, -1, 0, 1), glm::vec4(6, 0, 2, 1)};
  b.carry_velocity = {0.0f, 0.0f, -1.0f};
  const Bounds box = swept_bounds({a, b}, 3.0f);
  // a ends at x in [6, 7]; b ends at z in [-3, -1]; each grown by 5 % of its diagonal.
  const double grow_a = 0.05 * std::sqrt(3.0);
  const double grow_b = 0.05 * std::sqrt(1.0 + 1.0 + 4.0);
  EXPECT_NEAR(box.min.x, 0.0 - grow_a, 1e-9);
  EXPECT_NEAR(box.max.x, 7.0 + grow_a, 1e-9);
  EXPECT_NEAR(box.min.z, -3.0 - grow_b, 1e-9);
  EXPECT_NEAR(box.max.z, 2.0 + grow_b, 1e-9);
  EXPECT_NEAR(box.min.y, -1.0 - grow_b, 1e-9);
  EXPECT_NEAR(box.max.y, 1.0 + grow_a, 1e-9);
}

TEST(SweptBounds, NoNodesIsAnError) {
  EXPECT_THROW((void)swept_bounds({}, 1.0f), Error);
}

}  // namespace
}  // namespace deformcd::render
