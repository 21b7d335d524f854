#pragma once
// `deformcd info --gpu [--json]`: the OpenGL device behind a headless context and its compute
// limits. Only built with the GL backend (DEFORMCD_HAS_GL).

#include <ostream>

namespace deformcd::app {

/// Creates a headless GL context (DEFORMCD_EGL_PLATFORM chooses the EGL platform) and prints
/// the device and its compute limits to `out`: an aligned table, or one JSON object when
/// `json`. When no context can be had, prints why to std::cerr and returns 1; else returns 0.
int run_gpu_info(std::ostream& out, bool json);

}  // namespace deformcd::app
