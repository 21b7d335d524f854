// `deformcd run SCENE`: steps a scene headless and prints a summary.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "contacts_jsonl.h"
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
  std::optional<std::string> broadphase;
  std::string contacts_out;
  int threads = 0;
};

// What the run's collision passes found, for the summary.
struct ContactTally {
  std::uint64_t total = 0;
  std::uint64_t peak = 0;
  int frames_in_contact = 0;
  int first_frame = -1;
  int last_frame = -1;

  void add(int frame, std::uint64_t contacts) {
    if (contacts == 0) return;
    total += contacts;
    peak = std::max(peak, contacts);
    ++frames_in_contact;
    if (first_frame < 0) first_frame = frame;
    last_frame = frame;
  }
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
  options.broadphase = parse_broadphase(o.broadphase.value_or(scene.collision.broadphase));
  if (!o.contacts_out.empty() && options.broadphase == BroadPhase::kNone) {
    throw Error("--contacts needs a broad phase (brute or octree), not 'none'");
  }
  options.self_collision = scene.collision.self;
  World world(make_scene_bodies(scene, load_model_argument, frames), step_settings(scene.settings),
              options);
  if (!world.notice().empty()) std::cerr << "deformcd: " << world.notice() << '\n';

  // Opened before the run, so that a bad path fails at once; renamed into place at the end.
  std::optional<StreamedFileWriter> contacts_file;
  if (!o.contacts_out.empty()) contacts_file.emplace(o.contacts_out);
  const bool detecting = options.broadphase != BroadPhase::kNone;
  ContactTally tally;
  // Frame 0 is the initial pose; frame k the state after k steps.
  const auto record_contacts = [&] {
    if (!detecting) return;
    if (contacts_file) {
      const std::vector<Contact> contacts = world.contacts();
      contacts_file->append(contacts_json_line(world.frame(), contacts));
      tally.add(world.frame(), contacts.size());
    } else {
      tally.add(world.frame(), world.collision_counts().contacts);
    }
  };

  using Clock = std::chrono::steady_clock;
  Progress progress("simulating", frames);
  if (detecting) world.detect_collisions();
  record_contacts();
  world.finish();
  const auto start = Clock::now();
  for (int f = 0; f < frames; ++f) {
    world.step();
    record_contacts();
    progress.update(f + 1);
  }
  world.finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  progress.done();

  if (!o.positions_out.empty()) write_file_atomically(o.positions_out, positions_json(world));
  if (contacts_file) contacts_file->commit();

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
            << 1000.0 * seconds / frames << " ms per frame"
            << (detecting ? " (simulation and collision detection)" : "") << '\n';
  if (detecting) {
    std::cout << "collision  " << broadphase_name(options.broadphase) << ": "
              << tally.frames_in_contact << " frames in contact";
    if (tally.frames_in_contact > 0) {
      std::cout << " (" << tally.first_frame << "-" << tally.last_frame << "), " << tally.total
                << " face pairs in all, at most " << tally.peak << " in a frame";
    }
    std::cout << '\n';
  }
  if (!o.positions_out.empty()) std::cout << "positions  " << o.positions_out << '\n';
  if (!o.contacts_out.empty()) std::cout << "contacts   " << o.contacts_out << '\n';
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
  cmd->add_option(
      "--broadphase", o->broadphase,
      "Collision broad phase: none, brute, octree, octree-compact or bvh (default: the scene's)");
  cmd->add_option("--contacts", o->contacts_out,
                  "Write each frame's intersecting face pairs (JSON Lines, frames 0..N)");
  cmd->add_option("--positions-out", o->positions_out,
                  "Write the final node positions of every body (JSON)");
  return [o]() { return run(*o); };
}

}  // namespace deformcd::app
