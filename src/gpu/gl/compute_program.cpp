#include "compute_program.h"

#include <epoxy/gl.h>

#include <string>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "deformcd/error.h"
#include "gl_check.h"
#include "shader_log.h"
#include "shader_preprocessor.h"

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

// Compiles `source`, returning the shader object. Throws GlError with the mapped log.
GLuint compile(const std::string& name, const PreprocessedShader& source) {
  const GLuint shader = DEFORMCD_GL_CHECK(glCreateShader(GL_COMPUTE_SHADER));
  const char* text = source.text.c_str();
  DEFORMCD_GL_CHECK(glShaderSource(shader, 1, &text, nullptr));
  DEFORMCD_GL_CHECK(glCompileShader(shader));
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log =
        map_driver_log(info_log(shader, glGetShaderiv, glGetShaderInfoLog), source);
    glDeleteShader(shader);
    throw GlError("compiling compute shader '" + name + "' failed:\n" + log);
  }
  return shader;
}

}  // namespace

ComputeProgram::ComputeProgram(std::string_view name, const ShaderLibrary& library)
    : shader_name_(name) {
  const PreprocessedShader source = preprocess_shader(name, library);
  const GLuint shader = compile(shader_name_, source);
  program_ = DEFORMCD_GL_CHECK(glCreateProgram());
  DEFORMCD_GL_CHECK(glAttachShader(program_, shader));
  DEFORMCD_GL_CHECK(glLinkProgram(program_));
  // The program keeps the compiled code; the shader object is no longer needed.
  DEFORMCD_GL_CHECK(glDetachShader(program_, shader));
  glDeleteShader(shader);
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log =
        map_driver_log(info_log(program_, glGetProgramiv, glGetProgramInfoLog), source);
    glDeleteProgram(std::exchange(program_, 0));
    throw GlError("linking compute shader '" + shader_name_ + "' failed:\n" + log);
  }
  GLint size[3] = {0, 0, 0};
  DEFORMCD_GL_CHECK(glGetProgramiv(program_, GL_COMPUTE_WORK_GROUP_SIZE, size));
  for (GLuint axis = 0; axis < 3; ++axis) {
    work_group_size_[axis] = static_cast<std::uint32_t>(size[axis]);
    GLint max_count = 0;
    DEFORMCD_GL_CHECK(glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, axis, &max_count));
    max_work_group_count_[axis] = static_cast<std::uint32_t>(max_count);
  }
}

ComputeProgram::~ComputeProgram() {
  if (program_ != 0) glDeleteProgram(program_);
}

ComputeProgram::ComputeProgram(ComputeProgram&& other) noexcept
    : program_(std::exchange(other.program_, 0)),
      shader_name_(std::move(other.shader_name_)),
      work_group_size_(other.work_group_size_),
      max_work_group_count_(other.max_work_group_count_),
      uniform_locations_(std::move(other.uniform_locations_)) {}

ComputeProgram& ComputeProgram::operator=(ComputeProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    shader_name_ = std::move(other.shader_name_);
    work_group_size_ = other.work_group_size_;
    max_work_group_count_ = other.max_work_group_count_;
    uniform_locations_ = std::move(other.uniform_locations_);
  }
  return *this;
}

void ComputeProgram::use() const {
  DEFORMCD_GL_CHECK(glUseProgram(program_));
}

void ComputeProgram::dispatch(std::uint32_t groups_x, std::uint32_t groups_y,
                              std::uint32_t groups_z) const {
  const std::array<std::uint32_t, 3> groups = {groups_x, groups_y, groups_z};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (groups[axis] > max_work_group_count_[axis]) {
      throw GlError("dispatching '" + shader_name_ + "': " + std::to_string(groups[axis]) +
                    " work groups along " + "xyz"[axis] + " exceed the device's maximum of " +
                    std::to_string(max_work_group_count_[axis]));
    }
  }
  use();
  DEFORMCD_GL_CHECK(glDispatchCompute(groups_x, groups_y, groups_z));
}

void ComputeProgram::dispatch_covering(std::uint32_t invocations) const {
  const std::uint32_t local = work_group_size_[0];
  // Written to avoid overflowing near 2^32 invocations.
  const std::uint32_t groups = invocations / local + (invocations % local != 0 ? 1u : 0u);
  if (groups > 0) dispatch(groups);
}

int ComputeProgram::uniform_location(std::string_view name) {
  if (auto it = uniform_locations_.find(name); it != uniform_locations_.end()) return it->second;
  const std::string key(name);
  const GLint location = DEFORMCD_GL_CHECK(glGetUniformLocation(program_, key.c_str()));
  if (location < 0) {
    throw GlError("compute shader '" + shader_name_ + "' has no active uniform '" + key +
                  "' (misspelt, or unused and removed by the compiler)");
  }
  uniform_locations_.emplace(key, location);
  return location;
}

void ComputeProgram::set_uniform(std::string_view name, std::uint32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1ui(program_, uniform_location(name), value));
}

void ComputeProgram::set_uniform(std::string_view name, std::int32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1i(program_, uniform_location(name), value));
}

void ComputeProgram::set_uniform(std::string_view name, float value) {
  DEFORMCD_GL_CHECK(glProgramUniform1f(program_, uniform_location(name), value));
}

void ComputeProgram::set_uniform(std::string_view name, const glm::vec3& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniform3fv(program_, uniform_location(name), 1, glm::value_ptr(value)));
}

void ComputeProgram::set_uniform(std::string_view name, const glm::vec4& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniform4fv(program_, uniform_location(name), 1, glm::value_ptr(value)));
}

void storage_barrier() {
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT));
}

void memory_barrier(std::uint32_t barrier_bits) {
  DEFORMCD_GL_CHECK(glMemoryBarrier(barrier_bits));
}

}  // namespace deformcd::gl
