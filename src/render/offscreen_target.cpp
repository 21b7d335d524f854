#include "deformcd/render/offscreen_target.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::render {

namespace {

std::string framebuffer_status_name(GLenum status) {
  switch (status) {
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
      return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
      return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_UNSUPPORTED:
      return "GL_FRAMEBUFFER_UNSUPPORTED";
    default:
      return "status 0x" + std::to_string(status);
  }
}

// A renderbuffer of `format`, multisampled when samples > 1.
GLuint make_renderbuffer(GLenum format, int samples, int width, int height) {
  GLuint name = 0;
  DEFORMCD_GL_CHECK(glGenRenderbuffers(1, &name));
  DEFORMCD_GL_CHECK(glBindRenderbuffer(GL_RENDERBUFFER, name));
  if (samples > 1) {
    DEFORMCD_GL_CHECK(
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height));
  } else {
    DEFORMCD_GL_CHECK(glRenderbufferStorage(GL_RENDERBUFFER, format, width, height));
  }
  DEFORMCD_GL_CHECK(glBindRenderbuffer(GL_RENDERBUFFER, 0));
  return name;
}

void check_complete(const char* which) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError(std::string("offscreen target: the ") + which +
                  " framebuffer is incomplete: " + framebuffer_status_name(status));
  }
}

}  // namespace

OffscreenTarget::OffscreenTarget(int width, int height, int samples)
    : width_(width), height_(height) {
  GLint max_size = 0, max_samples = 0;
  DEFORMCD_GL_CHECK(glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size));
  DEFORMCD_GL_CHECK(glGetIntegerv(GL_MAX_SAMPLES, &max_samples));
  if (width <= 0 || height <= 0 || width > max_size || height > max_size) {
    throw GlError("offscreen target: " + std::to_string(width) + " x " + std::to_string(height) +
                  " pixels is not a size the device can render (each side 1 to " +
                  std::to_string(max_size) + ")");
  }
  samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));

  // Created before the checks that may throw below: the destructor does not run for a
  // constructor that throws, so a failure releases what exists so far itself.
  try {
    colour_ = make_renderbuffer(GL_RGBA8, samples_, width, height);
    depth_ = make_renderbuffer(GL_DEPTH_COMPONENT24, samples_, width, height);
    DEFORMCD_GL_CHECK(glGenFramebuffers(1, &draw_fbo_));
    DEFORMCD_GL_CHECK(glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_));
    DEFORMCD_GL_CHECK(
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_));
    DEFORMCD_GL_CHECK(
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_));
    check_complete("drawing");
    if (samples_ > 1) {
      resolve_colour_ = make_renderbuffer(GL_RGBA8, 1, width, height);
      DEFORMCD_GL_CHECK(glGenFramebuffers(1, &resolve_fbo_));
      DEFORMCD_GL_CHECK(glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_));
      DEFORMCD_GL_CHECK(glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                                  GL_RENDERBUFFER, resolve_colour_));
      check_complete("resolve");
    }
    DEFORMCD_GL_CHECK(glBindFramebuffer(GL_FRAMEBUFFER, 0));
  } catch (...) {
    release();
    throw;
  }
}

OffscreenTarget::~OffscreenTarget() {
  release();
}

void OffscreenTarget::release() noexcept {
  const GLuint framebuffers[] = {draw_fbo_, resolve_fbo_};
  const GLuint renderbuffers[] = {colour_, depth_, resolve_colour_};
  glDeleteFramebuffers(2, framebuffers);  // names 0 are ignored
  glDeleteRenderbuffers(3, renderbuffers);
  draw_fbo_ = resolve_fbo_ = colour_ = depth_ = resolve_colour_ = 0;
}

void OffscreenTarget::bind() const {
  DEFORMCD_GL_CHECK(glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_));
  DEFORMCD_GL_CHECK(glViewport(0, 0, width_, height_));
}

RgbaImage OffscreenTarget::read() const {
  GLuint source = draw_fbo_;
  if (resolve_fbo_ != 0) {
    DEFORMCD_GL_CHECK(glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_));
    DEFORMCD_GL_CHECK(glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_));
    DEFORMCD_GL_CHECK(glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_,
                                        GL_COLOR_BUFFER_BIT, GL_NEAREST));
    source = resolve_fbo_;
  }
  DEFORMCD_GL_CHECK(glBindFramebuffer(GL_READ_FRAMEBUFFER, source));
  DEFORMCD_GL_CHECK(glReadBuffer(GL_COLOR_ATTACHMENT0));
  RgbaImage image = read_framebuffer(width_, height_);
  DEFORMCD_GL_CHECK(glBindFramebuffer(GL_FRAMEBUFFER, 0));
  return image;
}

RgbaImage read_framebuffer(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw GlError("read_framebuffer: " + std::to_string(width) + " x " + std::to_string(height) +
                  " is not a size");
  }
  // Rows are tightly packed whatever the width.
  DEFORMCD_GL_CHECK(glPixelStorei(GL_PACK_ALIGNMENT, 1));
  const std::size_t row = 4 * static_cast<std::size_t>(width);
  std::vector<std::uint8_t> bottom_up(row * static_cast<std::size_t>(height));
  DEFORMCD_GL_CHECK(glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data()));
  // GL's first row is the bottom one; images start at the top.
  RgbaImage image{width, height, std::vector<std::uint8_t>(bottom_up.size())};
  for (int y = 0; y < height; ++y) {
    std::memcpy(image.pixels.data() + row * static_cast<std::size_t>(y),
                bottom_up.data() + row * static_cast<std::size_t>(height - 1 - y), row);
  }
  return image;
}

}  // namespace deformcd::render
