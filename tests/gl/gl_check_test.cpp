// DEFORMCD_GL_CHECK: names the failing call, file and line in debug builds; the KHR_debug
// message rides along in debug contexts.

#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <string>

#include "deformcd/error.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {
namespace {

class GlCheckTest : public test_support::GlTest {};

TEST_F(GlCheckTest, PassesValuesThrough) {
  const GLuint buffer = [] {
    GLuint name = 0;
    DEFORMCD_GL_CHECK(glGenBuffers(1, &name));
    return name;
  }();
  EXPECT_NE(buffer, 0u);
  EXPECT_EQ(DEFORMCD_GL_CHECK(glIsBuffer(buffer)), GL_FALSE);  // never bound: not yet a buffer
  glDeleteBuffers(1, &buffer);
}

#ifndef NDEBUG
TEST_F(GlCheckTest, FailingCallThrowsWithCallFileAndLine) {
  const int line = __LINE__ + 2;
  try {
    DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1u << 30, 0));
    FAIL() << "expected GlError";
  } catch (const GlError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("gl_check_test.cpp:" + std::to_string(line) +
                     ": GL_INVALID_VALUE after "
                     "glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1u << 30, 0)"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("KHR_debug"), std::string::npos) << m;
  }
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << "the error flags were drained";
}
#else
TEST_F(GlCheckTest, ReleaseBuildsDoNotCheck) {
  EXPECT_NO_THROW(DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1u << 30, 0)));
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}
#endif

}  // namespace
}  // namespace deformcd::gl
