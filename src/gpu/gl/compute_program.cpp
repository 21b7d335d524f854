#include "gpu/gl/compute_program.h"

#include <epoxy/gl.h>

#include <optional>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::gl {

ComputeProgram::ComputeProgram(std::string_view name, const ShaderLibrary& library)
    : shader_name_(name) {
  const PreprocessedShader source = preprocess_shader(name, library);
  const GLuint shader = compile_shader_stage(GL_COMPUTE_SHADER, "compute", shader_name_, source);
  program_ = DEFORMCD_GL_CHECK(glCreateProgram());
  DEFORMCD_GL_CHECK(glAttachShader(program_, shader));
  DEFORMCD_GL_CHECK(glLinkProgram(program_));
  // The program keeps the compiled code; the shader object is no longer needed.
  DEFORMCD_GL_CHECK(glDetachShader(program_, shader));
  glDeleteShader(shader);
  if (const std::optional<std::string> log = link_failure_log(program_, source)) {
    glDeleteProgram(std::exchange(program_, 0));
    throw GlError("linking compute shader '" + shader_name_ + "' failed:\n" + *log);
  }
  uniforms_ = ProgramUniforms(program_, "compute shader '" + shader_name_ + "' has");
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
      uniforms_(std::move(other.uniforms_)) {}

ComputeProgram& ComputeProgram::operator=(ComputeProgram&& other) noexcept {
  if (this != &other) {
    if (program_ != 0) glDeleteProgram(program_);
    program_ = std::exchange(other.program_, 0);
    shader_name_ = std::move(other.shader_name_);
    work_group_size_ = other.work_group_size_;
    max_work_group_count_ = other.max_work_group_count_;
    uniforms_ = std::move(other.uniforms_);
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

void ComputeProgram::set_uniform(std::string_view name, std::uint32_t value) {
  uniforms_.set(name, value);
}

void ComputeProgram::set_uniform(std::string_view name, std::int32_t value) {
  uniforms_.set(name, value);
}

void ComputeProgram::set_uniform(std::string_view name, float value) {
  uniforms_.set(name, value);
}

void ComputeProgram::set_uniform(std::string_view name, const glm::vec3& value) {
  uniforms_.set(name, value);
}

void ComputeProgram::set_uniform(std::string_view name, const glm::vec4& value) {
  uniforms_.set(name, value);
}

void storage_barrier() {
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT));
}

void memory_barrier(std::uint32_t barrier_bits) {
  DEFORMCD_GL_CHECK(glMemoryBarrier(barrier_bits));
}

}  // namespace deformcd::gl
