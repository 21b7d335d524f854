#pragma once
// The largest buffer a GL stage allocates: its option (max_buffer_bytes, 0 = none) within the
// device's GL_MAX_SHADER_STORAGE_BLOCK_SIZE, and whether that limit is the device's (so that a
// message names the right one). Shared by GlSimulation, GlCollision and GlContactResponse.

#include <algorithm>
#include <cstdint>

#include "deformcd/gl/device_info.h"

namespace deformcd::gl {

[[nodiscard]] inline std::uint64_t buffer_limit(const DeviceInfo& device, std::uint64_t option) {
  return option > 0 ? std::min(option, device.max_ssbo_block_bytes) : device.max_ssbo_block_bytes;
}

[[nodiscard]] inline bool limit_is_device(const DeviceInfo& device, std::uint64_t option) {
  return option == 0 || option >= device.max_ssbo_block_bytes;
}

}  // namespace deformcd::gl
