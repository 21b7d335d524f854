// `deformcd run SCENE`: steps a scene headless and prints a summary.

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "deformcd/world.h"
#include "model_input.h"
#include "progress.h"

namespace deformcd::app {

namespace {

struct RunOptions {
  std::string scene;
  std::optional<int> frames;
  std::string backend = "auto";
  std::string positions_out;
  int threads = 0;
};

std::string positions_json(const World& world) {
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    nlohmann::json positions = nlohmann::json::array();
    for (const glm::vec3& p : world.positions(b))
      positions.push_back({p.x, p.y, p.z});
    bodies.push_back({{"name", world.body_name(b)}, {"positions", std::move(positions)}});
  }
  return nlohmann::json{{"frame", world.frame()}, {"bodies", std::move(bodies)}}.dump() + "\n";
}

int run(const RunOptions& o) {
  const Scene scene = read_scene(o.scene);
  const int frames = o.frames.value_or(scene.settings.frames);
  if (frames < 1) throw Error("--frames must be at least 1");
  WorldOptions options;
  options.backend = parse_backend(o.backend);
  options.cpu_threads = o.threads;
  World world(make_scene_bodies(scene, load_model_argument, frames), step_settings(scene.settings),
              options);
  if (!world.notice().empty()) std::cerr << "deformcd: " << world.notice() << '\n';

  using Clock = std::chrono::steady_clock;
  Progress progress("simulating", frames);
  world.finish();
  const auto start = Clock::now();
  for (int f = 0; f < frames; ++f) {
    world.step();
    progress.update(f + 1);
  }
  world.finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  progress.done();

  if (!o.positions_out.empty()) write_file_atomically(o.positions_out, positions_json(world));

  std::size_t nodes = 0;
  for (std::size_t b = 0; b < world.body_count(); ++b)
    nodes += world.object(b).node_count;
  std::cout << "scene      " << o.scene << " (" << world.body_count() << " bodies, " << nodes
            << " nodes)\n"
            << "backend    " << world.backend_name() << " (" << world.device() << ")\n"
            << "frames     " << frames << " x " << scene.settings.substeps << " substeps, dt "
            << scene.settings.dt << " s (substep " << scene.settings.dt / scene.settings.substeps
            << " s; estimated stable up to " << world.estimated_max_substep() << " s)\n"
            << std::fixed << std::setprecision(3) << "time       " << seconds << " s, "
            << 1000.0 * seconds / frames << " ms per frame\n";
  if (!o.positions_out.empty()) std::cout << "positions  " << o.positions_out << '\n';
  return 0;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate a scene headless and print a summary");
  cmd->add_option("scene", o->scene, "Scene file (JSON)")->required();
  cmd->add_option("--frames", o->frames,
                  "Frames to run (default: the scene's); paths span exactly this many frames");
  cmd->add_option("--backend", o->backend, "gl, cpu, or auto (GL when available)")
      ->check(CLI::IsMember({"auto", "gl", "cpu"}));
  cmd->add_option("--threads", o->threads, "CPU backend threads (0: all cores)");
  cmd->add_option("--positions-out", o->positions_out,
                  "Write the final node positions of every body (JSON)");
  return [o]() { return run(*o); };
}

}  // namespace deformcd::app
