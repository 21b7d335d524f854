#pragma once
// Resolves `#include "name"` in GLSL before the driver sees it (core GLSL has no includes).
//
// Names are relative to shaders/ (not to the including file). Each file is included at most
// once per shader, like #pragma once, so common files may include each other; the #version line
// must come first in the shader itself and not at all in included files. Includes are expanded
// before any other preprocessing, so an #include inside #if 0 is still expanded.
//
// The driver compiles one string and numbers its lines 1, 2, 3...; `origins` maps those numbers
// back to files and lines (shader_log.h rewrites the driver's log with it). We do not rely on
// `#line L S` source-string numbers for this: Mesa reports some errors (undeclared identifiers,
// for one) with source string 0 whatever #line said, which would blame the wrong file.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace deformcd::gl {

class ShaderLibrary;

struct SourceLine {
  std::uint32_t file = 0;  // index into PreprocessedShader::files
  std::uint32_t line = 0;  // 1-based, in that file
};

struct PreprocessedShader {
  std::string text;                 // what is handed to glShaderSource
  std::vector<std::string> files;   // files[0] is the shader itself, then includes in order
  std::vector<SourceLine> origins;  // origins[n - 1]: where line n of `text` comes from
};

// Expands the includes of shader `name`. Throws GlError naming the file and line of a missing
// or misplaced #version, or of an include that cannot be resolved.
[[nodiscard]] PreprocessedShader preprocess_shader(std::string_view name,
                                                   const ShaderLibrary& library);

}  // namespace deformcd::gl
