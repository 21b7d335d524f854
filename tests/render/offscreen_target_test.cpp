// Offscreen targets (orientation of the read-back image, multisample resolve) and the drawing
// programs' error reports. Needs a GL 4.3 context (skips without, unless DEFORMCD_REQUIRE_GL).

#include <epoxy/gl.h>

#include <string>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/render/offscreen_target.h"
#include "gl/gl_test_context.h"
#include "render/graphics_program.h"
#include "render/render_embedded_shaders.h"

namespace deformcd::render {
namespace {

using gl::test_support::GlTest;

class OffscreenTargetTest : public GlTest {};

TEST_F(OffscreenTargetTest, ReadsBackTopRowFirstForEverySampleCount) {
  for (int samples : {1, 4}) {
    const OffscreenTarget target(6, 4, samples);
    target.bind();
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    // GL's y grows upwards: the scissored rectangle is the image's top-left quarter.
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 2, 3, 2);
    glClearColor(1.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    const RgbaImage image = target.read();
    ASSERT_EQ(image.width, 6);
    ASSERT_EQ(image.height, 4);
    ASSERT_EQ(image.pixels.size(), 6u * 4u * 4u);
    EXPECT_EQ(image.at(0, 0), glm::u8vec4(255, 0, 0, 255)) << samples << " samples";
    EXPECT_EQ(image.at(2, 1), glm::u8vec4(255, 0, 0, 255)) << samples << " samples";
    EXPECT_EQ(image.at(3, 0), glm::u8vec4(0, 0, 255, 255)) << samples << " samples";
    EXPECT_EQ(image.at(0, 3), glm::u8vec4(0, 0, 255, 255)) << samples << " samples";
  }
}

TEST_F(OffscreenTargetTest, ImpossibleSizesAreErrors) {
  EXPECT_THROW(OffscreenTarget(0, 10), GlError);
  EXPECT_THROW(OffscreenTarget(10, -1), GlError);
  EXPECT_THROW(OffscreenTarget(1 << 30, 10), GlError);
}

TEST_F(OffscreenTargetTest, EveryRenderShaderCompiles) {
  const gl::ShaderLibrary library = render_shader_library();
  for (const char* fragment : {"render/wire.frag", "render/collision.frag", "render/shaded.frag"})
    EXPECT_NO_THROW(GraphicsProgram("render/surface.vert", fragment, library)) << fragment;
}

TEST_F(OffscreenTargetTest, ACompileErrorNamesTheShaderFileAndLine) {
  gl::ShaderLibrary library = render_shader_library();
  library.add("render/broken.frag",
              "#version 430\n#include \"render/faces.glsl\"\nout vec4 o_colour;\n"
              "void main() {\n  o_colour = no_such_thing;\n}\n");
  try {
    GraphicsProgram program("render/surface.vert", "render/broken.frag", library);
    FAIL() << "a broken shader compiled";
  } catch (const GlError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("fragment shader 'render/broken.frag'"), std::string::npos) << message;
    EXPECT_NE(message.find("render/broken.frag:5"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace deformcd::render
