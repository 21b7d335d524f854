#pragma once
// Maps a driver's compile log back to our files. Drivers prefix messages with the source-string
// number (always 0: we pass one string) and the line in the preprocessed text; we replace both
// with the file and line it came from (PreprocessedShader::origins):
//   Mesa    "0:12(5): error: ..."    -> "common/layout.glsl:3(5): error: ..."
//   NVIDIA  "0(12) : error C0000..." -> "common/layout.glsl(3) : error C0000..."
//   AMD     "ERROR: 0:12: ..."       -> "ERROR: common/layout.glsl:3: ..."
// Lines in other formats, or with numbers out of range, are kept as they are.

#include <string>
#include <string_view>

#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::gl {

[[nodiscard]] std::string map_driver_log(std::string_view log, const PreprocessedShader& shader);

}  // namespace deformcd::gl
