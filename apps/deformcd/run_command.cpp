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
#include "option_values.h"
#include "output_paths.h"
#include "progress.h"
#include "response_summary.h"
#include "usage_error.h"

namespace deformcd::app {

namespace {

struct RunOptions {
  std::string scene;
  std::optional<int> frames;
  std::string backend = "auto";
  std::string positions_out;
  bool every_frame = false;
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

// One line: {"frame":k,"bodies":[{"name":...,"positions":[[x,y,z],...]},...]}.
std::string positions_json_line(const World& world) {
  nlohmann::json bodies = nlohmann::json::array();
  for (std::size_t b = 0; b < world.body_count(); ++b) {
    nlohmann::json positions = nlohmann::json::array();
    for (const glm::vec3& p : world.positions(b))
      positions.push_back({p.x, p.y, p.z});
    bodies.push_back({{"name", world.body_name(b)}, {"positions", std::move(positions)}});
  }
  return nlohmann::json{{"frame", world.frame()}, {"bodies", std::move(bodies)}}.dump() + "\n";
}

// Everything about the command line that can be checked without reading the scene.
void check_options(const RunOptions& o) {
  if (o.frames) check_at_least("--frames", *o.frames, 1);
  check_threads_option(o.threads);
  if (o.every_frame && o.positions_out.empty()) {
    throw UsageError("--every-frame writes the positions of every frame: give --positions FILE");
  }
  if (!o.contacts_out.empty() && o.broadphase == "none") {
    throw UsageError("--contacts needs a broad phase, not 'none'");
  }
  if (!o.contacts_out.empty()) check_output_file("--contacts", o.contacts_out);
  if (!o.positions_out.empty()) check_output_file("--positions", o.positions_out);
}

int run(const RunOptions& o) {
  check_options(o);
  const SummaryOnStderr summary_on_stderr(writes_stdout({o.contacts_out, o.positions_out}));
  status("reading " + o.scene);
  const Scene scene = read_scene(o.scene);
  const int frames = o.frames.value_or(scene.settings.frames);
  check_run_length(frames, scene.settings.substeps);
  WorldOptions options;
  options.backend = parse_backend(o.backend);
  options.cpu_threads = o.threads;
  options.broadphase = parse_broadphase(o.broadphase.value_or(scene.collision.broadphase));
  if (!o.contacts_out.empty() && options.broadphase == BroadPhase::kNone) {
    throw UsageError(o.scene +
                     " sets collision.broadphase 'none': give --broadphase with "
                     "--contacts");
  }
  options.self_collision = scene.collision.self;
  options.response = scene.response;
  status("building " + count_of(scene.bodies.size(), "body", "bodies"));
  std::vector<BodyInit> bodies = make_scene_bodies(scene, load_scene_model, frames);
  status("starting the " + o.backend + " backend");
  World world(bodies, step_settings(scene.settings), options);
  bodies.clear();
  if (!world.notice().empty()) std::cerr << "deformcd: " << world.notice() << '\n';

  // Opened before the run, so that a bad path fails at once; renamed into place at the end.
  std::optional<StreamedFileWriter> contacts_file;
  if (!o.contacts_out.empty()) contacts_file.emplace(o.contacts_out);
  std::optional<StreamedFileWriter> positions_file;
  if (!o.positions_out.empty()) positions_file.emplace(o.positions_out);
  const bool detecting = options.broadphase != BroadPhase::kNone;
  ContactTally tally;
  // Frame 0 is the initial pose; frame k the state after k steps.
  const auto record_frame = [&] {
    if (positions_file && (o.every_frame || world.frame() == frames)) {
      positions_file->append(positions_json_line(world));
    }
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
  if (detecting) world.detect_collisions();
  record_frame();
  world.finish();
  const auto start = Clock::now();
  Progress progress("simulating", frames);
  progress.update(0);
  ResponseTally response;
  for (int f = 0; f < frames; ++f) {
    world.step();
    record_frame();
    if (world.responds()) response.add(world.frame(), world.response_counts());
    progress.update(f + 1);
  }
  world.finish();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  progress.done();

  if (positions_file) positions_file->commit();
  if (contacts_file) contacts_file->commit();

  std::size_t nodes = 0;
  for (std::size_t b = 0; b < world.body_count(); ++b)
    nodes += world.object(b).node_count;
  std::cout << "scene      " << o.scene << " (" << count_of(world.body_count(), "body", "bodies")
            << ", " << count_of(nodes, "node", "nodes") << ")\n"
            << "backend    " << world.backend_name() << " (" << world.device() << ")\n"
            << "frames     " << frames << " x " << scene.settings.substeps << " substeps, dt "
            << scene.settings.dt << " s (substep " << scene.settings.dt / scene.settings.substeps
            << " s; estimated stable up to " << world.estimated_max_substep() << " s)\n"
            << std::fixed << std::setprecision(3) << "time       " << seconds << " s, "
            << 1000.0 * seconds / frames << " ms per frame"
            << (detecting ? " (simulation and collision detection)" : "") << '\n';
  if (detecting && !world.responds()) {
    std::cout << "collision  " << broadphase_name(options.broadphase) << ": "
              << count_of(tally.frames_in_contact, "frame", "frames") << " in contact";
    if (tally.frames_in_contact > 0) {
      std::cout << " (" << tally.first_frame << "-" << tally.last_frame << "), "
                << count_of(tally.total, "face pair", "face pairs") << " in all, at most "
                << tally.peak << " in a frame";
    }
    std::cout << '\n';
  }
  if (detecting && world.responds()) {
    // With contact response, intersecting faces are what the response is there to prevent:
    // none is its success, not a sign that the bodies never met (the line below says that).
    std::cout << "intersect  " << broadphase_name(options.broadphase) << ": ";
    if (tally.frames_in_contact == 0) {
      std::cout << "no intersecting faces in frames 0-" << frames
                << " (the response kept the surfaces apart)";
    } else {
      std::cout << "intersecting faces in " << tally.frames_in_contact << " of " << frames + 1
                << " frames (" << tally.first_frame << "-" << tally.last_frame << "), at most "
                << tally.peak << " face pairs in a frame (the response pushes them apart)";
    }
    std::cout << '\n';
  }
  if (world.responds()) {
    std::cout << "response   "
              << describe_response(response, world.body_count(), scene.response->sleep.has_value())
              << '\n';
  }
  if (!o.positions_out.empty()) {
    std::cout << "positions  " << o.positions_out
              << (o.every_frame ? " (frames 0.." + std::to_string(frames) + ")"
                                : " (frame " + std::to_string(frames) + ")")
              << '\n';
  }
  if (!o.contacts_out.empty()) std::cout << "contacts   " << o.contacts_out << '\n';
  return 0;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Simulate a scene headless and print a summary");
  cmd->add_option("scene", o->scene, "Scene file (JSON)")->required();
  add_frames_option(cmd, o->frames);
  cmd->add_option("--backend", o->backend, "auto (the library chooses GL or the CPU), gl or cpu")
      ->check(CLI::IsMember({"auto", "gl", "cpu"}))
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "CPU backend threads (0: all cores)")
      ->capture_default_str();
  add_broadphase_option(cmd, o->broadphase, true);
  cmd->add_option("--contacts", o->contacts_out,
                  "Write each frame's intersecting face pairs (JSON Lines, frames 0..N)");
  cmd->add_option("--positions", o->positions_out,
                  "Write the node positions of every body at the last frame (JSON)");
  cmd->add_flag("--every-frame", o->every_frame,
                "With --positions: every frame's positions, frames 0..N (JSON Lines)");
  return [o]() { return run(*o); };
}

}  // namespace deformcd::app
