#pragma once
/// \file image.h
/// RGBA8 images as the renderer reads them back, and PNG files.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec4.hpp>

namespace deformcd::render {

/// 8-bit RGBA pixels, row by row from the top-left corner (as image files store them).
struct RgbaImage {
  int width = 0;                     ///< pixels per row
  int height = 0;                    ///< rows
  std::vector<std::uint8_t> pixels;  ///< 4 x width x height bytes

  /// The pixel at column x, row y (0 = top). No bounds check.
  [[nodiscard]] glm::u8vec4 at(int x, int y) const {
    const std::size_t i = 4 * (static_cast<std::size_t>(y) * width + x);
    return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
  }
};

/// The PNG file (8-bit RGBA) of `image`. Throws Error when the image is empty or its pixel
/// count does not match its size.
[[nodiscard]] std::string encode_png(const RgbaImage& image);

/// Writes `image` as a PNG file, atomically: a failure leaves neither a partial file nor a
/// temporary. Throws Error naming the file.
void write_png(const std::filesystem::path& file, const RgbaImage& image);

/// Decodes a PNG file (any bit depth or colour type) to 8-bit RGBA. Throws Error naming
/// `origin` when the data is not a readable PNG.
[[nodiscard]] RgbaImage decode_png(std::string_view bytes, std::string_view origin = "PNG data");

/// Reads a PNG file to 8-bit RGBA. Throws Error naming the file.
[[nodiscard]] RgbaImage read_png(const std::filesystem::path& file);

}  // namespace deformcd::render
