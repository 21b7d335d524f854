#include "deformcd/gl/device_info.h"

#include <epoxy/gl.h>

#include <string>

#include "deformcd/gl/context.h"
#include "gpu/gl/gl_check.h"

namespace deformcd::gl {

namespace {

std::string gl_string(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(DEFORMCD_GL_CHECK(glGetString(name)));
  return text != nullptr ? text : "";
}

std::uint32_t gl_uint(GLenum name) {
  GLint value = 0;
  DEFORMCD_GL_CHECK(glGetIntegerv(name, &value));
  return static_cast<std::uint32_t>(value);
}

// Byte sizes may exceed 2^31 on big GPUs.
std::uint64_t gl_bytes(GLenum name) {
  GLint64 value = 0;
  DEFORMCD_GL_CHECK(glGetInteger64v(name, &value));
  return static_cast<std::uint64_t>(value);
}

std::array<std::uint32_t, 3> gl_uint3(GLenum name) {
  std::array<std::uint32_t, 3> xyz{};
  for (GLuint axis = 0; axis < 3; ++axis) {
    GLint value = 0;
    DEFORMCD_GL_CHECK(glGetIntegeri_v(name, axis, &value));
    xyz[axis] = static_cast<std::uint32_t>(value);
  }
  return xyz;
}

}  // namespace

DeviceInfo query_device_info(Context& context) {
  context.make_current();
  DeviceInfo info;
  info.vendor = gl_string(GL_VENDOR);
  info.renderer = gl_string(GL_RENDERER);
  info.gl_version = gl_string(GL_VERSION);
  info.gl_major = static_cast<int>(gl_uint(GL_MAJOR_VERSION));
  info.gl_minor = static_cast<int>(gl_uint(GL_MINOR_VERSION));
  info.glsl_version = gl_string(GL_SHADING_LANGUAGE_VERSION);
  info.platform = std::string(context.platform_name());
  info.platform_details = context.platform_details();
  info.debug_context = (gl_uint(GL_CONTEXT_FLAGS) & GL_CONTEXT_FLAG_DEBUG_BIT) != 0;

  info.max_work_group_count = gl_uint3(GL_MAX_COMPUTE_WORK_GROUP_COUNT);
  info.max_work_group_size = gl_uint3(GL_MAX_COMPUTE_WORK_GROUP_SIZE);
  info.max_work_group_invocations = gl_uint(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
  info.max_shared_memory_bytes = gl_bytes(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
  info.max_ssbo_block_bytes = gl_bytes(GL_MAX_SHADER_STORAGE_BLOCK_SIZE);
  info.max_ssbo_bindings = gl_uint(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
  info.max_compute_ssbo_blocks = gl_uint(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS);
  return info;
}

}  // namespace deformcd::gl
