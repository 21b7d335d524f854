#include "graphics_program.h"

#include <epoxy/gl.h>

#include <string>
#include <utility>

#include <glm/gtc/type_ptr.hpp>

#include "deformcd/error.h"
#include "gpu/gl/gl_check.h"
#include "gpu/gl/shader_log.h"
#include "gpu/gl/shader_preprocessor.h"

namespace deformcd::render {

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

// A compiled shader object, deleted on scope exit (the program keeps the code once linked).
class ShaderObject {
 public:
  ShaderObject(GLenum stage, std::string_view name, const gl::ShaderLibrary& library)
      : source_(gl::preprocess_shader(name, library)) {
    shader_ = DEFORMCD_GL_CHECK(glCreateShader(stage));
    const char* text = source_.text.c_str();
    DEFORMCD_GL_CHECK(glShaderSource(shader_, 1, &text, nullptr));
    DEFORMCD_GL_CHECK(glCompileShader(shader_));
    GLint ok = GL_FALSE;
    glGetShaderiv(shader_, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
      const std::string log =
          gl::map_driver_log(info_log(shader_, glGetShaderiv, glGetShaderInfoLog), source_);
      glDeleteShader(shader_);
      throw GlError(std::string("compiling ") +
                    (stage == GL_VERTEX_SHADER ? "vertex" : "fragment") + " shader '" +
                    std::string(name) + "' failed:\n" + log);
    }
  }
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
  GLint ok = GL_FALSE;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    // Link errors (mismatched interfaces) are mostly about the fragment stage's inputs; the
    // log's line numbers, if any, are mapped through its source.
    const std::string log = gl::map_driver_log(
        info_log(program_, glGetProgramiv, glGetProgramInfoLog), fragment_shader.source());
    glDeleteProgram(std::exchange(program_, 0));
    throw GlError("linking shaders '" + names_ + "' failed:\n" + log);
  }
}

GraphicsProgram::~GraphicsProgram() {
  if (program_ != 0) glDeleteProgram(program_);
}

void GraphicsProgram::use() const {
  DEFORMCD_GL_CHECK(glUseProgram(program_));
}

int GraphicsProgram::uniform_location(std::string_view name) {
  if (auto it = uniform_locations_.find(name); it != uniform_locations_.end()) return it->second;
  const std::string key(name);
  const GLint location = DEFORMCD_GL_CHECK(glGetUniformLocation(program_, key.c_str()));
  if (location < 0) {
    throw GlError("shaders '" + names_ + "' have no active uniform '" + key +
                  "' (misspelt, or unused and removed by the compiler)");
  }
  uniform_locations_.emplace(key, location);
  return location;
}

void GraphicsProgram::set_uniform(std::string_view name, std::int32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1i(program_, uniform_location(name), value));
}

void GraphicsProgram::set_uniform(std::string_view name, std::uint32_t value) {
  DEFORMCD_GL_CHECK(glProgramUniform1ui(program_, uniform_location(name), value));
}

void GraphicsProgram::set_uniform(std::string_view name, float value) {
  DEFORMCD_GL_CHECK(glProgramUniform1f(program_, uniform_location(name), value));
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::vec3& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniform3fv(program_, uniform_location(name), 1, glm::value_ptr(value)));
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::vec4& value) {
  DEFORMCD_GL_CHECK(
      glProgramUniform4fv(program_, uniform_location(name), 1, glm::value_ptr(value)));
}

void GraphicsProgram::set_uniform(std::string_view name, const glm::mat4& value) {
  DEFORMCD_GL_CHECK(glProgramUniformMatrix4fv(program_, uniform_location(name), 1, GL_FALSE,
                                              glm::value_ptr(value)));
}

}  // namespace deformcd::render
