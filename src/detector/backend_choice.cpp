#include "detector/backend_choice.h"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <utility>

#include "deformcd/error.h"
#include "deformcd/gl/context.h"  // declarations only: fine without the GL backend
#include "detector/gl_probe.h"

namespace deformcd {

namespace {

BackendChoice choose_gl(gl::Context* context) {
  if (!gl_backend_built()) {
    throw GlError(
        "this deformcd was built without the OpenGL backend (DEFORMCD_WITH_GL=OFF); the CPU "
        "backend (--backend cpu) is available");
  }
  BackendChoice choice;
  choice.kind = BackendKind::kGl;
  if (context == nullptr) {
    choice.owned_context = make_headless_gl_context();
    context = choice.owned_context.get();
  }
  context->make_current();
  choice.context = context;
  return choice;
}

BackendChoice cpu_with_notice(std::string notice) {
  BackendChoice cpu;
  cpu.notice = std::move(notice);
  return cpu;
}

std::string software_notice(const std::string& renderer) {
  return "the only OpenGL device is a software renderer (" + renderer +
         "), slower than the CPU backend: using the CPU (ask for the GL backend to run on it "
         "anyway)";
}

}  // namespace

bool is_software_renderer(const std::string& renderer) {
  std::string lower = renderer;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (std::string_view name : {"llvmpipe", "softpipe", "swrast", "software rasterizer"}) {
    if (lower.find(name) != std::string::npos) return true;
  }
  return false;
}

BackendKind parse_backend(std::string_view name) {
  if (name == "auto") return BackendKind::kAuto;
  if (name == "gl") return BackendKind::kGl;
  if (name == "cpu") return BackendKind::kCpu;
  throw Error("unknown backend '" + std::string(name) + "' (valid: auto, gl, cpu)");
}

BackendChoice choose_backend(BackendKind kind, gl::Context* context) {
  if (kind == BackendKind::kGl) return choose_gl(context);
  if (kind == BackendKind::kCpu) return {};
  if (context == nullptr) {
    // Look for a device in a child process first: a driver that crashes while it sets up a
    // context must not take the caller down with it.
    const GlProbe probe = probe_gl_in_child();
    switch (probe.outcome) {
      case GlProbe::Outcome::kCrashed:
        return cpu_with_notice("the OpenGL probe failed (" + probe.text +
                               "), using the CPU backend");
      case GlProbe::Outcome::kNoGl:
        return cpu_with_notice("OpenGL 4.3 is not available, using the CPU backend: " + probe.text);
      case GlProbe::Outcome::kRenderer:
        if (is_software_renderer(probe.text)) return cpu_with_notice(software_notice(probe.text));
        break;
      case GlProbe::Outcome::kNotRun:
        break;  // probe in this process, as below
    }
  }
  BackendChoice choice;
  try {
    choice = choose_gl(context);
  } catch (const GlError& e) {
    BackendChoice cpu;
    cpu.notice = std::string("OpenGL 4.3 is not available, using the CPU backend: ") + e.what();
    return cpu;
  }
  const std::string renderer = gl_renderer(*choice.context);
  if (is_software_renderer(renderer)) return cpu_with_notice(software_notice(renderer));
  return choice;
}

AutoBackend choose_auto_backend() {
  BackendChoice choice = choose_backend(BackendKind::kAuto, nullptr);
  return {choice.kind, std::move(choice.notice)};
}

std::string headless_gl_renderer() {
  const std::unique_ptr<gl::Context> context = make_headless_gl_context();
  context->make_current();
  return gl_renderer(*context);
}

}  // namespace deformcd
