// One mass-spring substep (springs, tetrahedron volume forces, gather, integration) on each
// backend, for the paper's four models, and for the 50k-face lion of the scaling scenes when
// scripts/make_models.sh --fine has made it. Reports ms per substep and springs per second; the
// CPU on 1 and on 2 threads (threads:N), for the thread scaling.
// GL timing: glFinish after every substep, so each iteration measures completed GPU work;
// wall-clock time (UseRealTime) on both backends, since llvmpipe and oneTBB work on other
// threads than the caller.

#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>

#include "core/sim/node_force_lists.h"
#include "cpu/cpu_simulation.h"
#include "deformcd/io.h"
#include "deformcd/simulation_state.h"
#ifdef DEFORMCD_HAS_GL
#include "deformcd/gl/context.h"
#include "gpu/gl/gl_simulation.h"
#endif

namespace {

using namespace deformcd;

SimulationState model_world(const std::string& name) {
  BodyOptions options;
  options.stiffness = 1.0e4;
  BodyInit init;
  init.body =
      build_body(read_tetgen(std::string(DEFORMCD_SOURCE_DIR) + "/assets/models/" + name), options);
  init.volume_stiffness = 1.0e4f;
  init.damping = 2.0e-4f;
  // A small squash so that every spring and tetrahedron carries a force.
  for (glm::vec4& p : init.body.positions)
    p.y *= 0.95f;
  return assemble_simulation({init});
}

void run(benchmark::State& state, sim::SimulationBackend& backend, const SimulationState& world) {
  backend.upload(world);
  const sim::SubstepConstants constants{1.0e-3f, glm::vec3(0.0f, -9.81f, 0.0f), 0.9998f};
  backend.substep(constants);  // warm-up: shader compilation, first touch of the buffers
  backend.finish();
  for (auto _ : state) {
    backend.substep(constants);
    backend.finish();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(world.springs.size()));
  state.counters["springs"] = static_cast<double>(world.springs.size());
  state.counters["nodes"] = static_cast<double>(world.node_count());
  state.counters["edges"] = static_cast<double>(sim::build_spring_edges(world).size());
}

void register_all() {
  for (const char* model : {"armadillo", "bunny", "dragon", "lion", "fine/lion_50k"}) {
    const std::string name(model);
    const std::string path = std::string(DEFORMCD_SOURCE_DIR) + "/assets/models/" + name;
    if (!std::filesystem::exists(path + ".node")) continue;  // a fine model not made
    for (int threads : {1, 2}) {
      benchmark::RegisterBenchmark(
          ("substep/cpu/" + name + "/threads:" + std::to_string(threads)).c_str(),
          [name, threads](benchmark::State& s) {
            cpu::CpuSimulation backend(threads);
            run(s, backend, model_world(name));
          })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
#ifdef DEFORMCD_HAS_GL
    benchmark::RegisterBenchmark(("substep/gl/" + name).c_str(),
                                 [name](benchmark::State& s) {
                                   static std::unique_ptr<gl::Context> context =
                                       gl::create_headless_context();
                                   gl::GlSimulation backend(*context);
                                   run(s, backend, model_world(name));
                                 })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
#endif
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
