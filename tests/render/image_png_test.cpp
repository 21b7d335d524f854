// PNG files: written atomically, read back pixel for pixel.

#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/render/image.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace deformcd::render {
namespace {

RgbaImage gradient(int width, int height) {
  RgbaImage image{width, height, std::vector<std::uint8_t>(4u * width * height)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      std::uint8_t* p = &image.pixels[4u * (y * width + x)];
      p[0] = static_cast<std::uint8_t>(x * 7);
      p[1] = static_cast<std::uint8_t>(y * 13);
      p[2] = static_cast<std::uint8_t>(x + y);
      p[3] = static_cast<std::uint8_t>(255 - x);
    }
  }
  return image;
}

class PngFiles : public ::testing::Test {
 protected:
  test::TempDir dir_;
};

TEST(Png, EncodeDecodeRoundTripsEveryPixel) {
  const RgbaImage image = gradient(37, 11);  // odd width: no row padding assumed
  const std::string png = encode_png(image);
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  const RgbaImage back = decode_png(png);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 11);
  EXPECT_EQ(back.pixels, image.pixels);
  EXPECT_EQ(back.at(3, 2), image.at(3, 2));
}

TEST(Png, BadImagesAndDataAreErrors) {
  EXPECT_THROW((void)encode_png(RgbaImage{}), Error);
  RgbaImage short_pixels = gradient(4, 4);
  short_pixels.pixels.pop_back();
  EXPECT_THROW((void)encode_png(short_pixels), Error);
  try {
    (void)decode_png("not a png at all", "garbage.png");
    FAIL() << "decoded garbage";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("garbage.png"), std::string::npos) << e.what();
  }
}

TEST_F(PngFiles, WriteThenReadGivesTheSameImageAndNoTemporaries) {
  const RgbaImage image = gradient(20, 30);
  const fs::path file = dir_ / "frame.png";
  write_png(file, image);
  const RgbaImage back = read_png(file);
  EXPECT_EQ(back.width, 20);
  EXPECT_EQ(back.height, 30);
  EXPECT_EQ(back.pixels, image.pixels);
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_.path()))
    ++entries;
  EXPECT_EQ(entries, 1);
}

TEST_F(PngFiles, WritingIntoAMissingDirectoryNamesTheFileAndLeavesNothing) {
  const fs::path file = dir_ / "missing" / "frame.png";
  try {
    write_png(file, gradient(2, 2));
    FAIL() << "wrote into a missing directory";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir_.path()));
}

TEST_F(PngFiles, ReadingAMissingFileNamesIt) {
  try {
    (void)read_png(dir_ / "nothing.png");
    FAIL() << "read a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nothing.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace deformcd::render
