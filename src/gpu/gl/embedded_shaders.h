#pragma once
// The GLSL files under shaders/, embedded at build time by cmake/EmbedShaders.cmake (the
// definition is generated into the build tree). EmbeddedShader is also the entry of the
// renderer's table (render/render_embedded_shaders.h).

#include <span>
#include <string_view>

namespace deformcd::gl {

struct EmbeddedShader {
  std::string_view name;    // path relative to shaders/, e.g. "common/layout.glsl"
  std::string_view source;  // the file's text
};

// Every embedded file, in the order CMake listed them.
std::span<const EmbeddedShader> embedded_shaders() noexcept;

// The source of `name`; throws GlError listing the embedded names when there is none.
std::string_view embedded_shader(std::string_view name);

}  // namespace deformcd::gl
