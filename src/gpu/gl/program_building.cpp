#include "gpu/gl/program_building.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <deque>
#include <optional>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "deformcd/error.h"
#include "gpu/gl/fault_injection.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/shader_log.h"

namespace deformcd::gl {

namespace {

// The info log of a shader (glGetShaderiv, glGetShaderInfoLog) or program (the glGetProgram*).
template <class GetParameter, class GetLog>
std::string info_log(GLuint object, GetParameter get_parameter, GetLog get_log) {
  GLint length = 0;
  get_parameter(object, GL_INFO_LOG_LENGTH, &length);
  if (length <= 0) return {};
  std::string log(static_cast<std::size_t>(length), '\0');
  GLsizei written = 0;
  get_log(object, length, &written, log.data());
  log.resize(static_cast<std::size_t>(written));
  return log;
}

// `source` with a line appended that uses an undeclared name, mapped to the line after the
// shader's own last: the driver then fails the compile with its own log
// (gl::fault::Kind::kShaderCompile). Not an #error: Mesa 22.3's shader cache gave the source
// with it the key of the source without it, skipped the compile and reported success.
PreprocessedShader with_injected_error(const PreprocessedShader& source) {
  PreprocessedShader failing = source;
  std::uint32_t last_line = 0;
  for (const SourceLine& origin : source.origins) {
    if (origin.file == 0) last_line = std::max(last_line, origin.line);
  }
  if (!failing.text.empty() && failing.text.back() != '\n') failing.text += '\n';
  failing.text += "uint injected = compile_failure_injected_by_gl_fault;\n";
  failing.origins.push_back({0, last_line + 1});
  return failing;
}

}  // namespace

std::uint32_t compile_shader_stage(std::uint32_t stage, std::string_view stage_name,
                                   std::string_view name, const PreprocessedShader& shader_source) {
  std::optional<PreprocessedShader> failing;
  if (fault::should_fail(fault::Kind::kShaderCompile)) failing = with_injected_error(shader_source);
  const PreprocessedShader& source = failing ? *failing : shader_source;
  const GLuint shader = DEFORMCD_GL_CHECK(glCreateShader(stage));
  const char* text = source.text.c_str();
  DEFORMCD_GL_CHECK(glShaderSource(shader, 1, &text, nullptr));
  DEFORMCD_GL_CHECK(glCompileShader(shader));
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log =
        map_driver_log(info_log(shader, glGetShaderiv, glGetShaderInfoLog), source);
    glDeleteShader(shader);
    throw GlError("compiling " + std::string(stage_name) + " shader '" + std::string(name) +
                  "' failed:\n" + log);
  }
  return shader;
}

std::optional<std::string> link_failure_log(std::uint32_t program,
                                            const PreprocessedShader& source) {
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return std::nullopt;
  return map_driver_log(info_log(program, glGetProgramiv, glGetProgramInfoLog), source);
}

namespace {

std::string_view stage_name(std::uint32_t stage) {
  switch (stage) {
    case GL_COMPUTE_SHADER:
      return "compute";
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    default:
      return "GL";
  }
}

// A compiled shader object, deleted on scope exit (the program keeps the code once linked).
class ShaderObject {
 public:
  ShaderObject(const ShaderStage& stage, const ShaderLibrary& library)
      : source_(preprocess_shader(stage.name, library)),
        shader_(compile_shader_stage(stage.stage, stage_name(stage.stage), stage.name, source_)) {}
  ~ShaderObject() { glDeleteShader(shader_); }
  ShaderObject(const ShaderObject&) = delete;
  ShaderObject& operator=(const ShaderObject&) = delete;

  [[nodiscard]] GLuint name() const { return shader_; }
  [[nodiscard]] const PreprocessedShader& source() const { return source_; }

 private:
  PreprocessedShader source_;
  GLuint shader_ = 0;
};

}  // namespace

Program::Program(std::initializer_list<ShaderStage> stages, const ShaderLibrary& library,
                 std::string_view what, std::string owner)
    : owner_(std::move(owner)) {
  std::deque<ShaderObject> shaders;  // compiled in order, deleted when the program has them
  for (const ShaderStage& stage : stages)
    shaders.emplace_back(stage, library);
  program_ = DEFORMCD_GL_CHECK(glCreateProgram());
  try {
    for (const ShaderObject& shader : shaders)
      DEFORMCD_GL_CHECK(glAttachShader(program_, shader.name()));
    DEFORMCD_GL_CHECK(glLinkProgram(program_));
    for (const ShaderObject& shader : shaders)
      DEFORMCD_GL_CHECK(glDetachShader(program_, shader.name()));
  } catch (...) {
    // A throwing constructor gets no destructor call.
    glDeleteProgram(std::exchange(program_, 0));
    throw;
  }
  if (const std::optional<std::string> log = link_failure_log(program_, shaders.back().source())) {
    glDeleteProgram(std::exchange(program_, 0));
    throw GlError("linking " + std::string(what) + " failed:\n" + *log);
  }
}

Program::~Program() {
  if (program_ != 0) glDeleteProgram(program_);
}

Program::Program(Program&& other) noexcept
    : program_(std::exchange(other.program_, 0)),
      owner_(std::move(other.owner_)),
      locations_(std::move(other.locations_)) {}

Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    owner_ = std::move(other.owner_);
    locations_ = std::move(other.locations_);
  }
  return *this;
}

void Program::use() const {
  DEFORMCD_GL_CHECK(glUseProgram(program_));
}

int Program::location(std::string_view name) {
  if (auto it = locations_.find(name); it != locations_.end()) return it->second;
  const std::string key(name);
  const GLint location = DEFORMCD_GL_CHECK(glGetUniformLocation(program_, key.c_str()));
  if (location < 0) {
    throw GlError(owner_ + " no active uniform '" + key +
                  "' (misspelt, or unused and removed by the compiler)");
  }
  locations_.emplace(key, location);
  return location;
}

void Program::set_uniform(std::string_view name, std::uint32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1ui(program_, location(name), value));
}

void Program::set_uniform(std::string_view name, std::int32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1i(program_, location(name), value));
}

void Program::set_uniform(std::string_view name, float value) {
  DEFORMCD_GL_CHECK(glProgramUniform1f(program_, location(name), value));
}

void Program::set_uniform(std::string_view name, const glm::vec3& value) {
  DEFORMCD_GL_CHECK(glProgramUniform3fv(program_, location(name), 1, glm::value_ptr(value)));
}

void Program::set_uniform(std::string_view name, const glm::vec4& value) {
  DEFORMCD_GL_CHECK(glProgramUniform4fv(program_, location(name), 1, glm::value_ptr(value)));
}

void Program::set_uniform(std::string_view name, const glm::mat4& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniformMatrix4fv(program_, location(name), 1, GL_FALSE, glm::value_ptr(value)));
}

}  // namespace deformcd::gl
