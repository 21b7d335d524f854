#pragma once
// Where shader sources come from: the embedded table, optionally overridden from a directory
// for developer reloads (DEFORMCD_SHADER_DIR), plus sources added in memory (tests, tools).

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>

namespace deformcd::gl {

class ShaderLibrary {
 public:
  // The embedded shaders. When the environment variable DEFORMCD_SHADER_DIR names a directory,
  // a file there (e.g. $DEFORMCD_SHADER_DIR/common/layout.glsl) takes precedence over the
  // embedded copy. Throws GlError when the variable is set but is not a directory.
  ShaderLibrary();

  // Adds `name`, or replaces it for this library only.
  void add(std::string name, std::string source);

  // The source of `name`. Throws GlError when no source has that name.
  [[nodiscard]] std::string source(std::string_view name) const;

 private:
  std::filesystem::path override_dir_;
  std::map<std::string, std::string, std::less<>> added_;
};

}  // namespace deformcd::gl
