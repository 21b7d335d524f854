// The embedded table holds the files under shaders/ byte for byte (no GL needed).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/embedded_shaders.h"

namespace deformcd::gl {
namespace {

std::string read_source_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(EmbeddedShaders, MatchTheFilesOnDisk) {
  const std::filesystem::path shaders = std::filesystem::path(DEFORMCD_SOURCE_DIR) / "shaders";
  ASSERT_GE(embedded_shaders().size(), 3u);
  for (const EmbeddedShader& shader : embedded_shaders()) {
    SCOPED_TRACE(std::string(shader.name));
    ASSERT_TRUE(std::filesystem::exists(shaders / shader.name));
    EXPECT_EQ(shader.source, read_source_file(shaders / shader.name));
  }
}

TEST(EmbeddedShaders, LookUpByName) {
  EXPECT_NE(embedded_shader("common/layout.glsl").find("struct ObjectInfo"), std::string::npos);
  EXPECT_NE(embedded_shader("common/layout.glsl").find("struct MeshInfo"), std::string::npos);
  EXPECT_NE(embedded_shader("collision/vertex_check.comp").find("atomicMin"), std::string::npos);
  EXPECT_THROW((void)embedded_shader("common/missing.glsl"), GlError);
}

}  // namespace
}  // namespace deformcd::gl
