#pragma once
// The renderer's GLSL files (shaders/render/), embedded at build time by
// cmake/EmbedShaders.cmake into deformcd_render (the definition is generated into the build
// tree), and the shader library that finds them along with deformcd_gl's shared files.

#include <span>

#include "gpu/gl/embedded_shaders.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::render {

using gl::EmbeddedShader;  // one entry per file, as deformcd_gl's

// Every embedded render shader, in the order CMake listed them.
std::span<const EmbeddedShader> embedded_shaders() noexcept;

// deformcd_gl's library (common/layout.glsl...) plus the render shaders. A render shader
// present under DEFORMCD_SHADER_DIR is read from there instead, as the compute shaders are.
[[nodiscard]] gl::ShaderLibrary render_shader_library();

}  // namespace deformcd::render
