#pragma once
/// \file device_info.h
/// What the GL device is and how much compute work it accepts.

#include <array>
#include <cstdint>
#include <string>

namespace deformcd::gl {

class Context;

/// The device behind a context and its compute limits, as the driver reports them.
struct DeviceInfo {
  std::string vendor;            ///< GL_VENDOR
  std::string renderer;          ///< GL_RENDERER
  std::string gl_version;        ///< GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
  int gl_major = 0;              ///< GL_MAJOR_VERSION
  int gl_minor = 0;              ///< GL_MINOR_VERSION
  std::string glsl_version;      ///< GL_SHADING_LANGUAGE_VERSION
  std::string platform;          ///< Context::platform_name()
  std::string platform_details;  ///< Context::platform_details()
  bool debug_context = false;    ///< GL_CONTEXT_FLAG_DEBUG_BIT is set

  std::array<std::uint32_t, 3> max_work_group_count{};  ///< per dispatch, x y z
  std::array<std::uint32_t, 3> max_work_group_size{};   ///< local size, x y z
  std::uint32_t max_work_group_invocations = 0;         ///< product of the local size
  std::uint64_t max_shared_memory_bytes = 0;            ///< GL_MAX_COMPUTE_SHARED_MEMORY_SIZE
  std::uint64_t max_ssbo_block_bytes = 0;               ///< GL_MAX_SHADER_STORAGE_BLOCK_SIZE
  std::uint32_t max_ssbo_bindings = 0;                  ///< GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS
  std::uint32_t max_compute_ssbo_blocks = 0;            ///< SSBOs one compute shader may use
};

/// Makes `context` current and queries it.
[[nodiscard]] DeviceInfo query_device_info(Context& context);

}  // namespace deformcd::gl
