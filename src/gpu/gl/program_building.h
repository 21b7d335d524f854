#pragma once
// What every GL program of the project does the same way, compute (ComputeProgram) or drawing
// (render::GraphicsProgram): compiling a preprocessed stage and reporting its log mapped back to
// file names, reading a link log, and setting uniforms by name with a clear error for a name
// the program does not have.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::gl {

/// Compiles `source` as a shader of GL stage `stage` (GL_COMPUTE_SHADER, ...) and returns the
/// shader object. Throws GlError "compiling <stage_name> shader '<name>' failed:" with the
/// driver's log mapped to file names and lines.
std::uint32_t compile_shader_stage(std::uint32_t stage, std::string_view stage_name,
                                   std::string_view name, const PreprocessedShader& source);

/// Nothing when `program` linked; otherwise its info log, mapped through `source`.
std::optional<std::string> link_failure_log(std::uint32_t program,
                                            const PreprocessedShader& source);

/// A program's uniforms by name (locations cached), set with glProgramUniform*.
class ProgramUniforms {
 public:
  /// `owner` starts the error for a missing uniform, e.g. "compute shader 'x.comp' has".
  ProgramUniforms(std::uint32_t program, std::string owner)
      : program_(program), owner_(std::move(owner)) {}

  /// Throw GlError when the program has no active uniform `name`: it is misspelt, or unused so
  /// that the compiler removed it.
  void set(std::string_view name, std::uint32_t value);
  void set(std::string_view name, std::int32_t value);
  void set(std::string_view name, float value);
  void set(std::string_view name, const glm::vec3& value);
  void set(std::string_view name, const glm::vec4& value);
  void set(std::string_view name, const glm::mat4& value);

 private:
  int location(std::string_view name);

  std::uint32_t program_ = 0;
  std::string owner_;
  std::map<std::string, int, std::less<>> locations_;
};

}  // namespace deformcd::gl
