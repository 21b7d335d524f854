#include "backend_factory.h"

#include "cpu/cpu_collision.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/gl/context.h"  // declarations only: fine without the GL backend
#ifdef DEFORMCD_HAS_GL
#include "gpu/gl/gl_collision.h"
#include "gpu/gl/gl_simulation.h"
#endif

namespace deformcd {

namespace {

CreatedBackend create_gl(const WorldOptions& options) {
#ifdef DEFORMCD_HAS_GL
  CreatedBackend created;
  gl::Context* context = options.gl_context;
  if (!context) {
    created.owned_context = gl::create_headless_context();
    context = created.owned_context.get();
  }
  auto simulation = std::make_unique<gl::GlSimulation>(*context);
  created.collision = std::make_unique<gl::GlCollision>(*context, *simulation);
  created.backend = std::move(simulation);
  return created;
#else
  (void)options;
  throw GlError(
      "this deformcd was built without the OpenGL backend (DEFORMCD_WITH_GL=OFF); the CPU "
      "backend (--backend cpu) is available");
#endif
}

CreatedBackend create_cpu(const WorldOptions& options) {
  CreatedBackend created;
  auto simulation = std::make_unique<cpu::CpuSimulation>(options.cpu_threads);
  created.collision = std::make_unique<cpu::CpuCollision>(*simulation);
  created.backend = std::move(simulation);
  return created;
}

}  // namespace

BackendKind parse_backend(std::string_view name) {
  if (name == "auto") return BackendKind::kAuto;
  if (name == "gl") return BackendKind::kGl;
  if (name == "cpu") return BackendKind::kCpu;
  throw Error("unknown backend '" + std::string(name) + "' (valid: auto, gl, cpu)");
}

CreatedBackend create_backend(const WorldOptions& options) {
  if (options.backend == BackendKind::kGl) return create_gl(options);
  if (options.backend == BackendKind::kAuto) {
    try {
      return create_gl(options);
    } catch (const GlError& e) {
      CreatedBackend created = create_cpu(options);
      created.notice =
          std::string("OpenGL 4.3 is not available, using the CPU backend: ") + e.what();
      return created;
    }
  }
  return create_cpu(options);
}

}  // namespace deformcd
