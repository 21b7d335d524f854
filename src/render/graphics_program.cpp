#include "render/graphics_program.h"

#include <epoxy/gl.h>

#include <optional>
#include <string>
#include <utility>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/program_building.h"
#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::render {

namespace {

// A compiled shader object, deleted on scope exit (the program keeps the code once linked).
class ShaderObject {
 public:
  ShaderObject(GLenum stage, std::string_view name, const gl::ShaderLibrary& library)
      : source_(gl::preprocess_shader(name, library)),
        shader_(gl::compile_shader_stage(stage, stage == GL_VERTEX_SHADER ? "vertex" : "fragment",
                                         name, source_)) {}
  ~ShaderObject() { glDeleteShader(shader_); }
  ShaderObject(const ShaderObject&) = delete;
  ShaderObject& operator=(const ShaderObject&) = delete;

  [[nodiscard]] GLuint name() const { return shader_; }
  [[nodiscard]] const gl::PreprocessedShader& source() const { return source_; }

 private:
  gl::PreprocessedShader source_;
  GLuint shader_ = 0;
};

}  // namespace

GraphicsProgram::GraphicsProgram(std::string_view vertex, std::string_view fragment,
                                 const gl::ShaderLibrary& library)
    : names_(std::string(vertex) + " + " + std::string(fragment)) {
  const ShaderObject vertex_shader(GL_VERTEX_SHADER, vertex, library);
  const ShaderObject fragment_shader(GL_FRAGMENT_SHADER, fragment, library);
  program_ = DEFORMCD_GL_CHECK(glCreateProgram());
  try {
    DEFORMCD_GL_CHECK(glAttachShader(program_, vertex_shader.name()));
    DEFORMCD_GL_CHECK(glAttachShader(program_, fragment_shader.name()));
    DEFORMCD_GL_CHECK(glLinkProgram(program_));
    DEFORMCD_GL_CHECK(glDetachShader(program_, vertex_shader.name()));
    DEFORMCD_GL_CHECK(glDetachShader(program_, fragment_shader.name()));
  } catch (...) {
    // A throwing constructor gets no destructor call.
    glDeleteProgram(std::exchange(program_, 0));
    throw;
  }
  // Link errors (mismatched interfaces) are mostly about the fragment stage's inputs; the
  // log's line numbers, if any, are mapped through its source.
  if (const std::optional<std::string> log =
          gl::link_failure_log(program_, fragment_shader.source())) {
    glDeleteProgram(std::exchange(program_, 0));
    throw GlError("linking shaders '" + names_ + "' failed:\n" + *log);
  }
  uniforms_ = gl::ProgramUniforms(program_, "shaders '" + names_ + "' have");
}

GraphicsProgram::~GraphicsProgram() {
  if (program_ != 0) glDeleteProgram(program_);
}

void GraphicsProgram::use() const {
  DEFORMCD_GL_CHECK(glUseProgram(program_));
}

void GraphicsProgram::set_uniform(std::string_view name, std::int32_t value) {
  uniforms_.set(name, value);
}

void GraphicsProgram::set_uniform(std::string_view name, std::uint32_t value) {
  uniforms_.set(name, value);
}

void GraphicsProgram::set_uniform(std::string_view name, float value) {
  uniforms_.set(name, value);
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::vec3& value) {
  uniforms_.set(name, value);
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::vec4& value) {
  uniforms_.set(name, value);
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::mat4& value) {
  uniforms_.set(name, value);
}

}  // namespace deformcd::render
