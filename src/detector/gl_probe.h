#pragma once
// The auto backend's look for a GL 4.3 device, made in a forked child process so that a driver
// crashing while it sets up a context (Mesa's llvmpipe under `ulimit -v 250000` dies of SIGSEGV)
// takes down the child, not the caller: the caller then runs on the CPU with a notice. The child
// asks backend_choice.h's headless_gl_renderer(); a build without the GL backend makes no child.

#include <string>

namespace deformcd {

/// What the child found.
struct GlProbe {
  enum class Outcome {
    kRenderer,  ///< a context was had; `text` is its GL_RENDERER
    kNoGl,      ///< no GL 4.3 context (GlError); `text` is the error
    kCrashed,   ///< the child died (a signal) or did not answer; `text` says how
    kNotRun,    ///< no child was made (no GL backend built, or fork or pipe failed): probe
                ///< in the process instead
  };
  Outcome outcome = Outcome::kNotRun;
  std::string text;
};

/// Creates a headless context in a forked child, reads its renderer and ends the child.
/// Waits at most `timeout_ms` for the answer (a child deadlocked after fork is killed).
[[nodiscard]] GlProbe probe_gl_in_child(int timeout_ms = 30000);

}  // namespace deformcd
