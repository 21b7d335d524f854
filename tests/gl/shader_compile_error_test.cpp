// Compile errors name the shader and the file and line the driver complained about, even
// inside an #include'd file.

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "deformcd/error.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/compute_program.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::gl {
namespace {

// The first line of `text` containing `word`, or "" when none does.
std::string line_mentioning(std::string_view word, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.find(word) != std::string::npos) return line;
  }
  return {};
}

class ShaderCompileErrorTest : public test_support::GlTest {
 protected:
  // The GlError message of compiling `name` from `library`.
  static std::string compile_error(std::string_view name, const ShaderLibrary& library) {
    try {
      ComputeProgram program(name, library);
    } catch (const GlError& e) {
      return e.what();
    }
    ADD_FAILURE() << name << " compiled";
    return {};
  }
};

TEST_F(ShaderCompileErrorTest, ErrorInAnIncludedFileNamesThatFileAndLine) {
  ShaderLibrary library;
  library.add("test/uses_broken.comp",
              "#version 430\n"
              "#include \"common/layout.glsl\"\n"
              "#include \"test/broken.glsl\"\n"
              "layout(local_size_x = 1) in;\n"
              "void main() { uint x = broken(); }\n");
  library.add("test/broken.glsl",
              "// line 1\n"
              "uint broken() {\n"
              "  return undefined_variable;\n"
              "}\n");
  const std::string message = compile_error("test/uses_broken.comp", library);
  EXPECT_NE(message.find("compiling compute shader 'test/uses_broken.comp' failed:"),
            std::string::npos)
      << message;
  // The driver's own words, mapped to the included file and its line 3.
  EXPECT_EQ(line_mentioning("undefined_variable", message).rfind("test/broken.glsl:3", 0), 0u)
      << message;
}

TEST_F(ShaderCompileErrorTest, ErrorAfterAnIncludeNamesTheTopFileAndItsOwnLine) {
  ShaderLibrary library;
  library.add("test/late_error.comp",
              "#version 430\n"
              "#include \"common/layout.glsl\"\n"
              "layout(local_size_x = 1) in;\n"
              "void main() {\n"
              "  SpringEdge s = not_declared;\n"
              "}\n");
  const std::string message = compile_error("test/late_error.comp", library);
  EXPECT_EQ(line_mentioning("not_declared", message).rfind("test/late_error.comp:5", 0), 0u)
      << message;
}

}  // namespace
}  // namespace deformcd::gl
