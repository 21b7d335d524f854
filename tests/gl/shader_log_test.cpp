// Mapping the driver's line numbers back to files and lines (no GL needed).

#include <gtest/gtest.h>

#include <string>

#include "gpu/gl/shader_library.h"
#include "gpu/gl/shader_log.h"
#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::gl {
namespace {

// Lines 1-2 of the text are top.comp:1-2, lines 3-4 are lib.glsl:1-2, line 5 is top.comp:4.
PreprocessedShader two_files() {
  ShaderLibrary library;
  library.add("top.comp", "#version 430\n// 2\n#include \"lib.glsl\"\n// 4\n");
  library.add("lib.glsl", "// 1\n// 2\n");
  return preprocess_shader("top.comp", library);
}

TEST(ShaderLog, MapsMesaNvidiaAndAmdPrefixes) {
  const PreprocessedShader shader = two_files();
  EXPECT_EQ(map_driver_log("0:4(5): error: `x' undeclared\n", shader),
            "lib.glsl:2(5): error: `x' undeclared\n");
  EXPECT_EQ(map_driver_log("0(5) : error C1008: undefined variable \"x\"", shader),
            "top.comp(4) : error C1008: undefined variable \"x\"");
  EXPECT_EQ(map_driver_log("ERROR: 0:3: 'x' : undeclared identifier\n", shader),
            "ERROR: lib.glsl:1: 'x' : undeclared identifier\n");
}

TEST(ShaderLog, MapsEveryLineAndLeavesOthersAlone) {
  EXPECT_EQ(
      map_driver_log("0:1(1): warning: w\nerror: linking failed\n0:3(3): error: e\n", two_files()),
      "top.comp:1(1): warning: w\nerror: linking failed\nlib.glsl:1(3): error: e\n");
}

TEST(ShaderLog, KeepsOutOfRangeOrMalformedNumbers) {
  const PreprocessedShader shader = two_files();
  EXPECT_EQ(map_driver_log("0:6(1): error: e", shader), "0:6(1): error: e");
  EXPECT_EQ(map_driver_log("0:0(1): error: e", shader), "0:0(1): error: e");
  EXPECT_EQ(map_driver_log("1:2(1): error: e", shader), "1:2(1): error: e");
  EXPECT_EQ(map_driver_log("0: no line", shader), "0: no line");
  EXPECT_EQ(map_driver_log("0:12345678901(1): e", shader), "0:12345678901(1): e");
  EXPECT_EQ(map_driver_log("", shader), "");
}

}  // namespace
}  // namespace deformcd::gl
