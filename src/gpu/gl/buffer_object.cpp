#include <epoxy/gl.h>

#include <string>
#include <utility>

#include "deformcd/error.h"
#include "deformcd/gl/ssbo.h"
#include "gpu/gl/buffer_from.h"
#include "gpu/gl/fault_injection.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

void check_range(const char* operation, std::size_t offset, std::size_t bytes, std::size_t size) {
  if (offset > size || bytes > size - offset) {
    throw GlError(std::string("BufferObject::") + operation + ": bytes [" + std::to_string(offset) +
                  ", " + std::to_string(offset) + " + " + std::to_string(bytes) +
                  ") exceed the buffer's " + std::to_string(size));
  }
}

}  // namespace

BufferObject::BufferObject(std::size_t bytes) : bytes_(bytes) {
  DEFORMCD_GL_CHECK(glGenBuffers(1, &name_));
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, name_));
  // Drain stale errors so that the check below is about this allocation only.
  while (glGetError() != GL_NO_ERROR) {
  }
  // DYNAMIC_COPY: written by shaders, occasionally read back. Checked in release builds too,
  // because running out of GPU memory is a boundary condition, not a bug.
  GLenum error = GL_OUT_OF_MEMORY;
  const bool injected = fault::should_fail(fault::Kind::kBufferAllocation);
  if (!injected) {
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr,
                 GL_DYNAMIC_COPY);
    error = glGetError();
  }
  if (error != GL_NO_ERROR) {
    glDeleteBuffers(1, &name_);
    throw GlError("glBufferData of " + std::to_string(bytes) + " bytes failed: " +
                  detail::gl_error_name(error) + (injected ? " (injected by gl::fault)" : ""));
  }
}

BufferObject::~BufferObject() {
  if (name_ != 0) glDeleteBuffers(1, &name_);
}

BufferObject::BufferObject(BufferObject&& other) noexcept
    : name_(std::exchange(other.name_, 0)), bytes_(std::exchange(other.bytes_, 0)) {}

BufferObject& BufferObject::operator=(BufferObject&& other) noexcept {
  if (this != &other) {
    if (name_ != 0) glDeleteBuffers(1, &name_);
    name_ = std::exchange(other.name_, 0);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void BufferObject::upload(const void* data, std::size_t bytes, std::size_t offset) {
  check_range("upload", offset, bytes, bytes_);
  if (bytes == 0) return;
  // Shader writes to the buffer must land before this copy overwrites them.
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT));
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, name_));
  DEFORMCD_GL_CHECK(glBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset),
                                    static_cast<GLsizeiptr>(bytes), data));
}

void BufferObject::download(void* out, std::size_t bytes, std::size_t offset) const {
  check_range("download", offset, bytes, bytes_);
  if (bytes == 0) return;
  // Makes shader writes visible to glGetBufferSubData; the read itself waits for them.
  DEFORMCD_GL_CHECK(glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT));
  DEFORMCD_GL_CHECK(glBindBuffer(GL_SHADER_STORAGE_BUFFER, name_));
  DEFORMCD_GL_CHECK(glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset),
                                       static_cast<GLsizeiptr>(bytes), out));
}

void BufferObject::bind_storage(std::uint32_t index) const {
  bind_storage_buffer(index, name_);
}

void bind_storage_buffer(std::uint32_t binding, std::uint32_t buffer) {
  DEFORMCD_GL_CHECK(glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer));
}

GlError allocation_error(const BufferLabel& label, std::uint64_t count, std::uint64_t element_bytes,
                         const GlError& cause) {
  std::string size = std::to_string(count * element_bytes) + " bytes";
  if (element_bytes > 1) {
    size += " (" + std::to_string(count) + " x " + std::to_string(element_bytes) + ")";
  }
  return GlError(std::string(label.owner) + ": allocating " + std::string(label.name) + " (SSBO " +
                 std::to_string(label.binding) + "), " + size + ", failed: " + cause.what());
}

}  // namespace deformcd::gl
