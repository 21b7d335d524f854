// #include resolution and source-string numbering (no GL needed).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "deformcd/error.h"
#include "gl/gl_test_context.h"
#include "gpu/gl/shader_library.h"
#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::gl {
namespace {

using test_support::ScopedEnv;

// "file:line" of every line of the preprocessed text.
std::string origins_of(const PreprocessedShader& shader) {
  std::string out;
  for (const SourceLine& origin : shader.origins) {
    out += (out.empty() ? "" : " ") + shader.files[origin.file] + ":" + std::to_string(origin.line);
  }
  return out;
}

std::string error_of(std::string_view name, const ShaderLibrary& library) {
  try {
    (void)preprocess_shader(name, library);
  } catch (const GlError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ShaderPreprocessor, ExpandsIncludesAndRecordsWhereEachLineComesFrom) {
  ShaderLibrary library;
  library.add("a.comp", "#version 430\n// a2\n#include \"b.glsl\"\n// a4\n");
  library.add("b.glsl", "// b1\n#include \"c.glsl\"\n// b3");  // no final newline
  library.add("c.glsl", "// c1\n");
  const PreprocessedShader out = preprocess_shader("a.comp", library);
  EXPECT_EQ(out.text, "#version 430\n// a2\n// b1\n// c1\n// b3\n// a4\n");
  EXPECT_EQ(out.files, (std::vector<std::string>{"a.comp", "b.glsl", "c.glsl"}));
  EXPECT_EQ(origins_of(out), "a.comp:1 a.comp:2 b.glsl:1 c.glsl:1 b.glsl:3 a.comp:4");
}

TEST(ShaderPreprocessor, IncludesEachFileOnce) {
  ShaderLibrary library;
  library.add("a.comp", "#version 430\n#include \"b.glsl\"\n#include \"b.glsl\"\nx\n");
  library.add("b.glsl", "#include \"a.comp\"\nb\n");  // a cycle back to the root is harmless
  const PreprocessedShader out = preprocess_shader("a.comp", library);
  EXPECT_EQ(out.text,
            "#version 430\n"
            "// #include \"a.comp\" (already included)\n"
            "b\n"
            "// #include \"b.glsl\" (already included)\n"
            "x\n");
  EXPECT_EQ(origins_of(out), "a.comp:1 b.glsl:1 b.glsl:2 a.comp:3 a.comp:4");
}

TEST(ShaderPreprocessor, KeepsCommentsBeforeVersion) {
  ShaderLibrary library;
  library.add("a.comp", "// header\r\n#version 430 core\r\n  #  include \"b.glsl\"\r\n");
  library.add("b.glsl", "b\n");
  EXPECT_EQ(preprocess_shader("a.comp", library).text, "// header\r\n#version 430 core\r\nb\n");
}

TEST(ShaderPreprocessor, MissingIncludeNamesTheIncludingFileAndLine) {
  ShaderLibrary library;
  library.add("a.comp", "#version 430\n\n#include \"nope.glsl\"\n");
  const std::string message = error_of("a.comp", library);
  EXPECT_EQ(message.rfind("a.comp:3: in #include \"nope.glsl\": no shader named 'nope.glsl'", 0),
            0u)
      << message;
}

TEST(ShaderPreprocessor, RejectsMisplacedOrMissingVersionAndMalformedIncludes) {
  ShaderLibrary library;
  library.add("no_version.comp", "void main() {}\n");
  library.add("include_first.comp", "#include \"b.glsl\"\n#version 430\n");
  library.add("versioned_include.comp", "#version 430\n#include \"v.glsl\"\n");
  library.add("v.glsl", "#version 430\n");
  library.add("malformed.comp", "#version 430\n#include <b.glsl>\n");
  library.add("b.glsl", "\n");
  EXPECT_EQ(error_of("no_version.comp", library),
            "no_version.comp: no #version line (it must come first, before any #include)");
  EXPECT_EQ(error_of("include_first.comp", library),
            "include_first.comp:1: #include before the #version line");
  EXPECT_EQ(error_of("versioned_include.comp", library),
            "versioned_include.comp:2: in #include \"v.glsl\": v.glsl:1: an included file must "
            "not have a #version line");
  EXPECT_EQ(error_of("malformed.comp", library),
            "malformed.comp:2: malformed #include; write #include \"path/under/shaders.glsl\"");
}

TEST(ShaderLibrary, ShaderDirOverridesEmbeddedFiles) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("deformcd_shader_dir_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "test");
  std::ofstream(dir / "test" / "smoke.comp") << "#version 430\n// edited\n";
  {
    ScopedEnv env("DEFORMCD_SHADER_DIR", dir.string());
    const ShaderLibrary library;
    EXPECT_EQ(library.source("test/smoke.comp"), "#version 430\n// edited\n");
    // Files not in the directory still come from the embedded table.
    EXPECT_NE(library.source("common/layout.glsl").find("struct SpringEdge"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}

TEST(ShaderLibrary, ShaderDirThatIsNotADirectoryIsAnError) {
  ScopedEnv env("DEFORMCD_SHADER_DIR", "/nonexistent/deformcd/shaders");
  EXPECT_THROW(ShaderLibrary{}, GlError);
}

}  // namespace
}  // namespace deformcd::gl
