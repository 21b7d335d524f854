#pragma once
// Judging rendered images: the paper's collision colours, the white background, and screen
// rectangles to count pixels in.

#include <algorithm>
#include <limits>

#include <glm/vec2.hpp>

#include "deformcd/render/image.h"

namespace deformcd::test {

// The collision colours as drawn, (1,0,0) and (0,0,1); pixels where multisampling blended them
// with something else do not count.
inline bool is_red(const glm::u8vec4& p) {
  return p.r >= 200 && p.g <= 60 && p.b <= 60;
}
inline bool is_blue(const glm::u8vec4& p) {
  return p.b >= 200 && p.r <= 60 && p.g <= 60;
}
inline bool is_background(const glm::u8vec4& p) {
  return p.r == 255 && p.g == 255 && p.b == 255;
}

// A pixel rectangle, [x0, x1] x [y0, y1], rows from the top.
struct ScreenBox {
  float x0 = std::numeric_limits<float>::max(), y0 = std::numeric_limits<float>::max();
  float x1 = std::numeric_limits<float>::lowest(), y1 = std::numeric_limits<float>::lowest();

  void add(const glm::vec2& p) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  [[nodiscard]] ScreenBox grown(float by) const { return {x0 - by, y0 - by, x1 + by, y1 + by}; }
  // Whether the centre of pixel (x, y) lies in the box.
  [[nodiscard]] bool contains(int x, int y) const {
    const float cx = static_cast<float>(x) + 0.5f, cy = static_cast<float>(y) + 0.5f;
    return cx >= x0 && cx <= x1 && cy >= y0 && cy <= y1;
  }
  [[nodiscard]] float area() const { return std::max(0.0f, x1 - x0) * std::max(0.0f, y1 - y0); }
};

// Red and blue pixels, and how many of them lie outside a given box.
struct PixelCounts {
  int red = 0, blue = 0, red_outside = 0, blue_outside = 0;
};

inline PixelCounts count_collision_pixels(const render::RgbaImage& image, const ScreenBox& inside) {
  PixelCounts n;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::u8vec4 p = image.at(x, y);
      if (is_red(p)) {
        ++n.red;
        if (!inside.contains(x, y)) ++n.red_outside;
      } else if (is_blue(p)) {
        ++n.blue;
        if (!inside.contains(x, y)) ++n.blue_outside;
      }
    }
  }
  return n;
}

// The share of non-background pixels in `box`.
inline double coverage(const render::RgbaImage& image, const ScreenBox& box) {
  int drawn = 0, all = 0;
  const int x0 = std::max(0, static_cast<int>(box.x0));
  const int x1 = std::min(image.width - 1, static_cast<int>(box.x1));
  const int y0 = std::max(0, static_cast<int>(box.y0));
  const int y1 = std::min(image.height - 1, static_cast<int>(box.y1));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      ++all;
      if (!is_background(image.at(x, y))) ++drawn;
    }
  }
  return all > 0 ? static_cast<double>(drawn) / all : 0.0;
}

// The mean of (r + g + b) / 3 over the pixels in `box` that show a body's own colour (neither
// the background nor a collision colour).
inline double mean_brightness(const render::RgbaImage& image, const ScreenBox& box) {
  double sum = 0.0;
  int drawn = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const glm::u8vec4 p = image.at(x, y);
      if (!box.contains(x, y) || is_background(p) || is_red(p) || is_blue(p)) continue;
      sum += (p.r + p.g + p.b) / 3.0;
      ++drawn;
    }
  }
  return drawn > 0 ? sum / drawn : 0.0;
}

// How many pixels of `image` satisfy `is`.
template <class Predicate>
int count_pixels(const render::RgbaImage& image, Predicate is) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      n += is(image.at(x, y)) ? 1 : 0;
  return n;
}

}  // namespace deformcd::test
