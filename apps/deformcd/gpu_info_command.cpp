// `deformcd info --gpu`: see gpu_info_command.h.

#include "gpu_info_command.h"

#include <array>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "deformcd/backend.h"
#include "deformcd/error.h"
#include "deformcd/gl/context.h"
#include "deformcd/gl/device_info.h"

namespace deformcd::app {

namespace {

template <class T>
std::string xyz(const std::array<T, 3>& v) {
  return std::to_string(v[0]) + " x " + std::to_string(v[1]) + " x " + std::to_string(v[2]);
}

std::string bytes_and_mib(std::uint64_t bytes) {
  std::ostringstream text;
  text << bytes << " bytes (" << std::fixed << std::setprecision(1)
       << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB)";
  return text.str();
}

// What the backend `auto` (run's default, bench's) chooses given this device, in words.
std::string auto_backend_text(const AutoBackend& choice) {
  return choice.kind == BackendKind::kGl ? "gl (a hardware device)" : "cpu: " + choice.reason;
}

void print_table(std::ostream& out, const gl::DeviceInfo& d, const AutoBackend& choice) {
  const std::pair<const char*, std::string> rows[] = {
      {"vendor", d.vendor},
      {"renderer", d.renderer},
      {"GL version", d.gl_version},
      {"GLSL version", d.glsl_version},
      {"platform", d.platform + ", " + d.platform_details},
      {"debug context", d.debug_context ? "yes" : "no"},
      {"max work-group count", xyz(d.max_work_group_count)},
      {"max work-group size", xyz(d.max_work_group_size)},
      {"max invocations", std::to_string(d.max_work_group_invocations) + " per work group"},
      {"max shared memory", std::to_string(d.max_shared_memory_bytes) + " bytes"},
      {"max SSBO size", bytes_and_mib(d.max_ssbo_block_bytes)},
      {"max SSBO bindings", std::to_string(d.max_ssbo_bindings)},
      {"max compute SSBOs", std::to_string(d.max_compute_ssbo_blocks) + " per shader"},
      {"software renderer", is_software_renderer(d.renderer) ? "yes" : "no"},
      {"backend auto", auto_backend_text(choice)},
  };
  for (const auto& [label, value] : rows) {
    out << std::left << std::setw(22) << label << value << '\n';
  }
}

nlohmann::json to_json(const gl::DeviceInfo& d, const AutoBackend& choice) {
  return {
      // What the library makes of the device: scripts choose their work from these
      // (scripts/run.sh), not from the renderer's name.
      {"software_renderer", is_software_renderer(d.renderer)},
      {"auto_backend", choice.kind == BackendKind::kGl ? "gl" : "cpu"},
      {"auto_backend_reason", choice.reason},
      {"vendor", d.vendor},
      {"renderer", d.renderer},
      {"gl_version", d.gl_version},
      {"gl_major", d.gl_major},
      {"gl_minor", d.gl_minor},
      {"glsl_version", d.glsl_version},
      {"platform", d.platform},
      {"platform_details", d.platform_details},
      {"debug_context", d.debug_context},
      {"max_work_group_count", d.max_work_group_count},
      {"max_work_group_size", d.max_work_group_size},
      {"max_work_group_invocations", d.max_work_group_invocations},
      {"max_shared_memory_bytes", d.max_shared_memory_bytes},
      {"max_ssbo_bytes", d.max_ssbo_block_bytes},
      {"max_ssbo_bindings", d.max_ssbo_bindings},
      {"max_compute_ssbo_blocks", d.max_compute_ssbo_blocks},
  };
}

}  // namespace

int run_gpu_info(std::ostream& out, bool json) {
  gl::DeviceInfo info;
  try {
    const std::unique_ptr<gl::Context> context = gl::create_headless_context();
    info = gl::query_device_info(*context);
  } catch (const GlError& e) {
    std::cerr << "deformcd: " << e.what() << '\n';
    return 1;
  }
  const AutoBackend choice = choose_auto_backend();
  if (json) {
    out << to_json(info, choice).dump(2) << '\n';
  } else {
    print_table(out, info, choice);
  }
  return 0;
}

}  // namespace deformcd::app
