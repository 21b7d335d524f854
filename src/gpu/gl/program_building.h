#pragma once
// What every GL program of the project does the same way, compute (ComputeProgram) or drawing
// (render::GraphicsProgram): compiling its preprocessed stages and reporting a log mapped back to
// file names, linking them, owning the program, and setting uniforms by name with a clear error
// for a name the program does not have.

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "gpu/gl/shader_library.h"
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

/// One stage of a program: GL_COMPUTE_SHADER, GL_VERTEX_SHADER or GL_FRAGMENT_SHADER, and the
/// shader's name in its library (e.g. "render/surface.vert").
struct ShaderStage {
  std::uint32_t stage = 0;
  std::string_view name;
};

/// A linked program, compute (ComputeProgram) or drawing (render::GraphicsProgram): owns the GL
/// program and sets its uniforms by name.
class Program {
 public:
  /// Compiles `stages` from `library` (each with its #includes; "compiling <stage> shader
  /// '<name>' failed:") and links them. Throws GlError "linking <what> failed:" with the driver's
  /// log mapped through the last stage's source: a link error is mostly about its inputs.
  /// `owner` starts the error for a missing uniform, e.g. "compute shader 'x.comp' has".
  Program(std::initializer_list<ShaderStage> stages, const ShaderLibrary& library,
          std::string_view what, std::string owner);
  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  void use() const;

  /// Uniform setters (glProgramUniform*, no use() needed). Throw GlError when the program has
  /// no active uniform `name`: it is misspelt, or unused so that the compiler removed it.
  void set_uniform(std::string_view name, std::uint32_t value);
  void set_uniform(std::string_view name, std::int32_t value);
  void set_uniform(std::string_view name, float value);
  void set_uniform(std::string_view name, const glm::vec3& value);
  void set_uniform(std::string_view name, const glm::vec4& value);
  void set_uniform(std::string_view name, const glm::mat4& value);

  [[nodiscard]] std::uint32_t name() const noexcept { return program_; }

 private:
  int location(std::string_view name);

  std::uint32_t program_ = 0;
  std::string owner_;
  std::map<std::string, int, std::less<>> locations_;  // cached
};

}  // namespace deformcd::gl
