// Mesa's llvmpipe (22.3) leaks 112 bytes once per process, on the first draw call or blit, in
// a library it unloads at exit: LeakSanitizer then reports frames in "<unknown module>", which
// no suppression can name, and an ASan build of these tests would fail on the driver's leak.
// This environment makes that first draw with leak detection off for the calling thread (the
// allocation happens there), so every later allocation, ours included, is still checked.
// Outside sanitizer builds the LSan entry points are absent (weak) and nothing is disabled.

#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include "gl/gl_test_context.h"

extern "C" void __lsan_disable() __attribute__((weak));
extern "C" void __lsan_enable() __attribute__((weak));

namespace deformcd::test {
namespace {

class FirstDrawLeakGuard : public ::testing::Environment {
 public:
  void SetUp() override {
    gl::test_support::ContextAttempt& shared = gl::test_support::shared_context();
    if (!shared.context) return;  // the GL tests skip (or fail) on their own
    shared.context->make_current();
    if (__lsan_disable) __lsan_disable();
    draw_one_triangle();
    if (__lsan_enable) __lsan_enable();
  }

 private:
  static GLuint compile(GLenum stage, const char* source) {
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    return shader;
  }

  // A triangle into a one-pixel framebuffer, then a blit from it (both paths allocate).
  static void draw_one_triangle() {
    GLuint renderbuffers[2] = {0, 0}, framebuffers[2] = {0, 0}, vertex_array = 0;
    glGenRenderbuffers(2, renderbuffers);
    glGenFramebuffers(2, framebuffers);
    for (int i = 0; i < 2; ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, renderbuffers[i]);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, i == 0 ? 4 : 0, GL_RGBA8, 1, 1);
      glBindFramebuffer(GL_FRAMEBUFFER, framebuffers[i]);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                renderbuffers[i]);
    }
    const GLuint program = glCreateProgram();
    const GLuint vertex = compile(GL_VERTEX_SHADER,
                                  "#version 430\nvoid main() { gl_Position = vec4(vec2[3]("
                                  "vec2(-1), vec2(3, -1), vec2(-1, 3))[gl_VertexID], 0, 1); }\n");
    const GLuint fragment =
        compile(GL_FRAGMENT_SHADER, "#version 430\nout vec4 c;\nvoid main() { c = vec4(1); }\n");
    glAttachShader(program, vertex);
    glAttachShader(program, fragment);
    glLinkProgram(program);
    glGenVertexArrays(1, &vertex_array);
    glBindVertexArray(vertex_array);
    glUseProgram(program);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffers[0]);
    glViewport(0, 0, 1, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffers[0]);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffers[1]);
    glBlitFramebuffer(0, 0, 1, 1, 0, 0, 1, 1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glFinish();
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteVertexArrays(1, &vertex_array);
    glDeleteProgram(program);
    glDeleteShader(vertex);
    glDeleteShader(fragment);
    glDeleteFramebuffers(2, framebuffers);
    glDeleteRenderbuffers(2, renderbuffers);
  }
};

// Registered before main() runs the tests (gtest_main).
[[maybe_unused]] ::testing::Environment* const kGuard =
    ::testing::AddGlobalTestEnvironment(new FirstDrawLeakGuard);

}  // namespace
}  // namespace deformcd::test
