#include "program_building.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include "deformcd/error.h"
#include "gl_check.h"
#include "shader_log.h"

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

}  // namespace

std::uint32_t compile_shader_stage(std::uint32_t stage, std::string_view stage_name,
                                   std::string_view name, const PreprocessedShader& source) {
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

int ProgramUniforms::location(std::string_view name) {
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

void ProgramUniforms::set(std::string_view name, std::uint32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1ui(program_, location(name), value));
}

void ProgramUniforms::set(std::string_view name, std::int32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1i(program_, location(name), value));
}

void ProgramUniforms::set(std::string_view name, float value) {
  DEFORMCD_GL_CHECK(glProgramUniform1f(program_, location(name), value));
}

void ProgramUniforms::set(std::string_view name, const glm::vec3& value) {
  DEFORMCD_GL_CHECK(glProgramUniform3fv(program_, location(name), 1, glm::value_ptr(value)));
}

void ProgramUniforms::set(std::string_view name, const glm::vec4& value) {
  DEFORMCD_GL_CHECK(glProgramUniform4fv(program_, location(name), 1, glm::value_ptr(value)));
}

void ProgramUniforms::set(std::string_view name, const glm::mat4& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniformMatrix4fv(program_, location(name), 1, GL_FALSE, glm::value_ptr(value)));
}

}  // namespace deformcd::gl
