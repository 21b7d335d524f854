#include <cstdlib>
#include <filesystem>
#include <string>

#include "render/render_embedded_shaders.h"

namespace deformcd::render {

gl::ShaderLibrary render_shader_library() {
  gl::ShaderLibrary library;
  const char* dir = std::getenv("DEFORMCD_SHADER_DIR");
  for (const EmbeddedShader& shader : embedded_shaders()) {
    // Sources added to a library take precedence over its override directory, so a shader
    // overridden there must not be added.
    if (dir != nullptr && *dir != '\0' &&
        std::filesystem::is_regular_file(std::filesystem::path(dir) / shader.name)) {
      continue;
    }
    library.add(std::string(shader.name), std::string(shader.source));
  }
  return library;
}

}  // namespace deformcd::render
