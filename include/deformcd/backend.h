#pragma once
/// \file backend.h
/// Which backend runs a world or a detector: OpenGL 4.3 compute shaders or the CPU.

#include <string>
#include <string_view>

namespace deformcd {

/// Which backend runs a world or a detector.
enum class BackendKind {
  /// GL when a 4.3 context on a hardware device can be had, else the CPU (with a notice saying
  /// why): a software rasterizer (llvmpipe, softpipe, swrast) is slower than the CPU backend,
  /// so kAuto never picks it; ask for kGl to run on it anyway.
  kAuto,
  kGl,   ///< OpenGL 4.3 compute shaders (any device, software ones included); throws GlError
         ///< when no 4.3 context can be had
  kCpu,  ///< multithreaded CPU (oneTBB)
};

/// "auto", "gl" or "cpu"; throws Error listing the valid names otherwise.
[[nodiscard]] BackendKind parse_backend(std::string_view name);

/// What kAuto chooses on this machine.
struct AutoBackend {
  BackendKind kind = BackendKind::kCpu;  ///< kGl (a hardware GL 4.3 device) or kCpu
  std::string reason;                    ///< why the CPU, as a World's notice says; empty for GL
};

/// Applies kAuto's rule as a World or a Detector does (tries a headless GL 4.3 context and looks
/// at its device), for a program that chooses more than one backend from it (deformcd bench:
/// both on a hardware device, else the CPU alone).
[[nodiscard]] AutoBackend choose_auto_backend();

/// Whether a GL_RENDERER string (or a device description holding it) names a software
/// rasterizer: llvmpipe, softpipe, swrast. There GL runs on the CPU's cores, and its times,
/// timer queries included (deformcd/gl/timer_query.h), are CPU times.
[[nodiscard]] bool is_software_renderer(const std::string& renderer);

}  // namespace deformcd
