// The renderer on the paper's phase 1 (armadillo and lion), drawn from the GL world's buffers:
// colliding faces in red (body 0) and blue (body 1) exactly where the bodies intersect, none
// while they are apart, every body's wireframe where the body is.

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/render/offscreen_target.h"
#include "deformcd/render/scene_renderer.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "gl/gl_test_context.h"
#include "render/pixel_checks.h"
#include "support/world_fixtures.h"

namespace fs = std::filesystem;

namespace deformcd::render {
namespace {

using gl::test_support::GlTest;
using test::count_collision_pixels;
using test::coverage;
using test::is_background;
using test::mean_brightness;
using test::PixelCounts;
using test::ScreenBox;

constexpr int kWidth = 320;
constexpr int kHeight = 240;
constexpr float kAspect = static_cast<float>(kWidth) / kHeight;
// With 24 frames the bodies interpenetrate from frame 9 to 15; at 12 they overlap the most.
constexpr int kTotalFrames = 24;
constexpr int kContactFrame = 12;

// The phase 1 world on GL, shared by the tests (building it takes seconds on llvmpipe).
struct Phase1 {
  std::vector<BodyInit> bodies;
  StepSettings settings;
  Camera camera;
  std::unique_ptr<World> world;

  explicit Phase1(gl::Context& context) {
    const Scene scene = read_scene(fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / "phase1.json");
    bodies = make_scene_bodies(scene, read_tetgen, kTotalFrames);
    settings = step_settings(scene.settings);
    camera = Camera::framing(swept_bounds(bodies, kTotalFrames * settings.dt), kAspect);
    context_ = &context;
  }

  // The world at `frame`, with its collisions detected by the paper's octree.
  World& at(int frame) {
    if (!world || world->frame() > frame) {
      WorldOptions options;
      options.backend = BackendKind::kGl;
      options.gl_context = context_;
      options.broadphase = BroadPhase::kNone;  // stepping needs no collision passes
      world = std::make_unique<World>(bodies, settings, options);
    }
    while (world->frame() < frame)
      world->step();
    world->set_broadphase(BroadPhase::kOctree);
    world->detect_collisions();
    world->set_broadphase(BroadPhase::kNone);
    return *world;
  }

  [[nodiscard]] glm::vec2 to_pixels(const glm::vec3& p) const {
    const glm::vec4 clip = camera.view_projection(kAspect) * glm::vec4(p, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {(ndc.x + 1.0f) / 2.0f * kWidth, (1.0f - ndc.y) / 2.0f * kHeight};
  }

  [[nodiscard]] RgbaImage draw(RenderMode mode, bool show_collisions = true) const {
    const SceneRenderer renderer(*world);
    const OffscreenTarget target(kWidth, kHeight);
    target.bind();
    DrawOptions options;
    options.mode = mode;
    options.show_collisions = show_collisions;
    renderer.draw(camera, kWidth, kHeight, options);
    return target.read();
  }

  // Where body `b` is on screen now.
  [[nodiscard]] ScreenBox body_box(std::size_t b) const {
    ScreenBox box;
    for (const glm::vec3& p : world->positions(b))
      box.add(to_pixels(p));
    return box;
  }

  // Where the colliding faces can be drawn: the projected intersection segments, grown by the
  // largest projected size of a colliding face (every face holds its segments, so no point of
  // it is farther than its size from them), plus 2 pixels for rasterization.
  [[nodiscard]] ScreenBox contact_box(const std::vector<Contact>& contacts) const {
    std::vector<std::vector<glm::vec3>> positions;
    for (std::size_t b = 0; b < world->body_count(); ++b)
      positions.push_back(world->positions(b));
    ScreenBox box;
    float face_size = 0.0f;
    for (const Contact& c : contacts) {
      for (const ContactFace* f : {&c.a, &c.b}) {
        ScreenBox face;
        for (std::uint32_t node : f->nodes)
          face.add(to_pixels(positions[f->body][node]));
        face_size = std::max({face_size, face.x1 - face.x0, face.y1 - face.y0});
        if (c.coplanar) {  // no segment: the faces themselves
          box.add({face.x0, face.y0});
          box.add({face.x1, face.y1});
        }
      }
      if (!c.coplanar) {
        box.add(to_pixels(c.segment[0]));
        box.add(to_pixels(c.segment[1]));
      }
    }
    return box.grown(face_size + 2.0f);
  }

 private:
  gl::Context* context_ = nullptr;
};

class SceneRendererTest : public GlTest {
 protected:
  static Phase1& phase1(gl::Context& context) {
    static Phase1 shared(context);
    return shared;
  }
};

TEST_F(SceneRendererTest, BodiesApartShowTheirWireframesAndNoCollisionColours) {
  Phase1& scene = phase1(context());
  const World& world = scene.at(0);
  ASSERT_TRUE(world.contacts().empty());
  const RgbaImage image = scene.draw(RenderMode::kWireframe);
  const PixelCounts n = count_collision_pixels(image, ScreenBox{});
  EXPECT_EQ(n.red, 0);
  EXPECT_EQ(n.blue, 0);
  for (std::size_t b = 0; b < 2; ++b) {
    const ScreenBox box = scene.body_box(b);
    EXPECT_GT(box.area(), 400.0f) << "body " << b << " is too small to judge";
    EXPECT_GT(coverage(image, box), 0.3) << "body " << b << "'s wireframe is missing";
  }
  // Nothing is drawn outside the bodies.
  const ScreenBox a = scene.body_box(0).grown(2.0f), b = scene.body_box(1).grown(2.0f);
  int stray = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (!a.contains(x, y) && !b.contains(x, y) && !is_background(image.at(x, y))) ++stray;
  EXPECT_EQ(stray, 0);
}

TEST_F(SceneRendererTest, CollidingFacesAreRedAndBlueWhereTheBodiesIntersect) {
  Phase1& scene = phase1(context());
  const World& world = scene.at(kContactFrame);
  const std::vector<Contact> contacts = world.contacts();
  ASSERT_FALSE(contacts.empty());
  const ScreenBox region = scene.contact_box(contacts);
  // The region must be a proper part of the image for "inside it" to mean something.
  ASSERT_LT(region.area(), 0.5f * kWidth * kHeight);

  const RgbaImage wire = scene.draw(RenderMode::kWireframe);
  const PixelCounts n = count_collision_pixels(wire, region);
  EXPECT_GE(n.red, 20);
  EXPECT_GE(n.blue, 20);
  EXPECT_EQ(n.red_outside, 0);
  EXPECT_EQ(n.blue_outside, 0);
  for (std::size_t b = 0; b < 2; ++b)
    EXPECT_GT(coverage(wire, scene.body_box(b)), 0.3) << "body " << b;

  const RgbaImage shaded = scene.draw(RenderMode::kShaded);
  const PixelCounts s = count_collision_pixels(shaded, region);
  EXPECT_GE(s.red, 20);
  EXPECT_GE(s.blue, 20);
  EXPECT_EQ(s.red_outside, 0);
  EXPECT_EQ(s.blue_outside, 0);
  // Lit light-coloured faces instead of dark edges.
  for (std::size_t b = 0; b < 2; ++b) {
    EXPECT_GT(coverage(shaded, scene.body_box(b)), 0.3) << "body " << b;
    EXPECT_GT(mean_brightness(shaded, scene.body_box(b)),
              mean_brightness(wire, scene.body_box(b)) + 30.0)
        << "body " << b;
  }
  EXPECT_NE(shaded.pixels, wire.pixels);

  // Without the flags, no colour: e.g. when no collision pass ran.
  const PixelCounts off =
      count_collision_pixels(scene.draw(RenderMode::kWireframe, /*show_collisions=*/false), region);
  EXPECT_EQ(off.red + off.blue, 0);
}

TEST(SceneRenderer, ACpuWorldIsAClearError) {
  std::vector<BodyInit> bodies(1);
  bodies[0].body = build_body(test::tet_grid(1, 1, 1, 1.0));
  WorldOptions options;
  options.backend = BackendKind::kCpu;
  const World world(bodies, StepSettings{}, options);
  try {
    const SceneRenderer renderer(world);
    FAIL() << "drew a CPU world";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("cpu backend"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deformcd::render
