#include "gpu/gl/shader_library.h"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>

#include "deformcd/error.h"
#include "gpu/gl/embedded_shaders.h"

namespace deformcd::gl {

std::string_view embedded_shader(std::string_view name) {
  std::string known;
  for (const EmbeddedShader& shader : embedded_shaders()) {
    if (shader.name == name) return shader.source;
    known += known.empty() ? "" : ", ";
    known += shader.name;
  }
  throw GlError("no shader named '" + std::string(name) + "' (embedded: " + known + ")");
}

ShaderLibrary::ShaderLibrary() {
  const char* dir = std::getenv("DEFORMCD_SHADER_DIR");
  if (dir == nullptr || *dir == '\0') return;
  override_dir_ = dir;
  if (!std::filesystem::is_directory(override_dir_)) {
    throw GlError(std::string("DEFORMCD_SHADER_DIR=") + dir + " is not a directory");
  }
}

void ShaderLibrary::add(std::string name, std::string source) {
  added_.insert_or_assign(std::move(name), std::move(source));
}

std::string ShaderLibrary::source(std::string_view name) const {
  if (auto it = added_.find(name); it != added_.end()) return it->second;
  if (!override_dir_.empty()) {
    const std::filesystem::path path = override_dir_ / name;
    if (std::filesystem::is_regular_file(path)) {
      std::ifstream in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      if (!in) throw GlError(path.string() + ": cannot read the shader");
      return text.str();
    }
  }
  return std::string(embedded_shader(name));
}

}  // namespace deformcd::gl
