// PNG through stb_image_write / stb_image (Debian's libstb). Chosen over libpng because it
// encodes to memory in one call with no setjmp/longjmp error handling (which does not mix with
// C++ destructors), and the memory buffer then goes through write_file_atomically.

#include <stb_image.h>
#include <stb_image_write.h>

#include <climits>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/render/image.h"

namespace deformcd::render {

namespace {

void append_to_string(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<std::size_t>(size));
}

}  // namespace

std::string encode_png(const RgbaImage& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw Error("encode_png: the image is empty (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + ")");
  }
  const std::size_t expected =
      4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.pixels.size() != expected || image.width > INT_MAX / 4) {
    throw Error("encode_png: " + std::to_string(image.pixels.size()) + " bytes of pixels for a " +
                std::to_string(image.width) + " x " + std::to_string(image.height) +
                " RGBA image (" + std::to_string(expected) + " expected)");
  }
  std::string png;
  if (stbi_write_png_to_func(append_to_string, &png, image.width, image.height, 4,
                             image.pixels.data(), 4 * image.width) == 0) {
    throw Error("encode_png: stb_image_write could not encode the image (out of memory?)");
  }
  return png;
}

void write_png(const std::filesystem::path& file, const RgbaImage& image) {
  write_file_atomically(file, encode_png(image));
}

RgbaImage decode_png(std::string_view bytes, std::string_view origin) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
    throw Error(std::string(origin) + ": too large to decode");
  }
  int width = 0, height = 0, channels = 0;
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
      stbi_load_from_memory(data, static_cast<int>(bytes.size()), &width, &height, &channels, 4),
      stbi_image_free);
  if (!pixels) {
    throw Error(std::string(origin) + ": not a readable PNG (" + stbi_failure_reason() + ")");
  }
  RgbaImage image{width, height, {}};
  image.pixels.assign(pixels.get(), pixels.get() + 4 * static_cast<std::size_t>(width) * height);
  return image;
}

RgbaImage read_png(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open the file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (!in) throw Error(file.string() + ": cannot read the file");
  return decode_png(bytes.str(), file.string());
}

}  // namespace deformcd::render
