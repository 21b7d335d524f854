#pragma once
/// \file offscreen_target.h
/// A framebuffer to render into without a window: colour and depth renderbuffers, multisampled
/// when the device allows, resolved and read back as an RgbaImage. Needs a current GL 4.3
/// context (e.g. gl::create_headless_context()) for every call, destruction included.

#include <cstdint>

#include "deformcd/render/image.h"

namespace deformcd::render {

/// A multisampled framebuffer (colour and depth renderbuffers) to draw into without a
/// window, and read back as an image.
class OffscreenTarget {
 public:
  /// A width x height target with `samples` samples per pixel (clamped to the device's
  /// GL_MAX_SAMPLES; 0 or 1 for none). Throws GlError when a size is not positive or exceeds
  /// GL_MAX_RENDERBUFFER_SIZE, or when the framebuffer is incomplete.
  OffscreenTarget(int width, int height, int samples = 4);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// Binds the framebuffer for drawing and sets the viewport to cover it.
  void bind() const;
  /// Resolves the samples and reads the pixels back (waits for the drawing to finish). Leaves
  /// the default framebuffer (0) bound.
  [[nodiscard]] RgbaImage read() const;

  [[nodiscard]] int width() const { return width_; }    ///< pixels
  [[nodiscard]] int height() const { return height_; }  ///< pixels
  /// Samples per pixel actually used (1 when not multisampled).
  [[nodiscard]] int samples() const { return samples_; }

 private:
  void release() noexcept;

  int width_;
  int height_;
  int samples_ = 1;
  std::uint32_t draw_fbo_ = 0;
  std::uint32_t colour_ = 0;
  std::uint32_t depth_ = 0;
  // The single-sample copy the multisampled image is resolved into (0 when not multisampled).
  std::uint32_t resolve_fbo_ = 0;
  std::uint32_t resolve_colour_ = 0;
};

/// Reads width x height pixels from the bound read framebuffer's read buffer (e.g. a window's
/// back buffer before the swap). Waits for the drawing to finish.
[[nodiscard]] RgbaImage read_framebuffer(int width, int height);

}  // namespace deformcd::render
