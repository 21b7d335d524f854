#include "bench_runner.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <numeric>

#include "bench_device_timer.h"
#include "bench_intersections.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "model_input.h"

namespace deformcd::app {

namespace {

std::string_view backend_label(BackendKind kind) {
  return kind == BackendKind::kGl ? "gl" : kind == BackendKind::kCpu ? "cpu" : "auto";
}

// `world` gives the backend, threads and self-collision; the method and timing are set here.
// The two stages run apart, so that each is bracketed by its own clock readings and timer query:
// step() simulates only (broad phase kNone), then detect_collisions() runs the method as step()
// would after the simulation. Each wall-clock reading follows a wait for the backend (glFinish on
// GL); the collision stage includes the wait for the pass (collision_counts(): complete(), a
// rerun after an overflow). The queries end right after the stage's commands, before the waits,
// and are read after the clock has stopped.
MethodRun measure(const std::vector<BodyInit>& bodies, const StepSettings& settings,
                  WorldOptions world_options, BroadPhase method, int frames,
                  const std::function<void()>& frame_done, std::string& device) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  world_options.broadphase = method;
  // With contact response, step() times its proximity and response stages (waiting for the
  // backend around each projection); without, nothing inside step() waits.
  world_options.measure_stage_times = world_options.response.has_value();
  World world(bodies, settings, world_options);
  device = world.device();
  StageDeviceTimer timer(world.backend_name() == "gl");
  BenchIntersections census(world, bodies);
  MethodRun run;
  run.method = method;
  // The response's first frame starts from the exact intersections of the start pose, as
  // step() finds them when no pass has run yet (untimed: step() would time it as collision).
  // Without it a start in contact was simulated without its untangling in the first frame.
  if (world.responds()) world.detect_collisions();
  for (int f = 0; f < frames; ++f) {
    world.set_broadphase(BroadPhase::kNone);
    auto start = Clock::now();
    timer.begin(BenchStage::kSimulation);
    world.step();
    timer.end(BenchStage::kSimulation);
    world.finish();
    run.simulation_s.push_back(seconds_since(start));
    if (world.responds()) {
      run.proximity_s.push_back(world.last_frame_times().proximity_s);
      run.response_s.push_back(world.last_frame_times().response_s);
      const ResponseCounts counts = world.response_counts();
      run.searches.push_back(counts.searches);
      run.widenings.push_back(counts.widenings);
      run.self_searches.push_back(counts.self_searches);
      run.substeps.push_back(counts.substeps);
      run.iterations.push_back(counts.iterations);
      run.asleep.push_back(counts.asleep);
      run.constraints.push_back(counts.contact_constraints());
      run.constraints_between.push_back(counts.between_bodies);
    }

    world.set_broadphase(method);
    start = Clock::now();
    timer.begin(BenchStage::kCollision);
    world.detect_collisions();
    timer.end(BenchStage::kCollision);
    const CollisionCounts counts = world.collision_counts();
    world.finish();
    run.collision_s.push_back(seconds_since(start));

    if (const auto s = timer.seconds(BenchStage::kSimulation))
      run.simulation_device_s.push_back(*s);
    if (const auto s = timer.seconds(BenchStage::kCollision)) run.collision_device_s.push_back(*s);
    run.contacts.push_back(counts.contacts);
    run.candidates.push_back(counts.candidates);
    census.record(run.intersections, run.inverted_tetrahedra);  // untimed
    frame_done();
  }
  return run;
}

std::vector<Stage> stages_from(const std::vector<std::uint64_t>& contacts) {
  const auto first = std::find_if(contacts.begin(), contacts.end(), [](auto c) { return c > 0; });
  const auto last = std::find_if(contacts.rbegin(), contacts.rend(), [](auto c) { return c > 0; });
  std::vector<Stage> stages(contacts.size(), kBefore);
  if (first == contacts.end()) return stages;  // never in contact: all "before"
  const auto begin = static_cast<std::size_t>(first - contacts.begin());
  const auto end = contacts.size() - static_cast<std::size_t>(last - contacts.rbegin());
  for (std::size_t f = begin; f < contacts.size(); ++f)
    stages[f] = f < end ? kContact : kAfter;
  return stages;
}

}  // namespace

double MethodRun::total_proximity_s() const {
  return std::accumulate(proximity_s.begin(), proximity_s.end(), 0.0);
}

double MethodRun::total_response_s() const {
  return std::accumulate(response_s.begin(), response_s.end(), 0.0);
}

double MethodRun::response_ratio(bool in_contact) const {
  double response = 0.0, simulation = 0.0;
  for (std::size_t f = 0; f < constraints_between.size(); ++f) {
    if ((constraints_between[f] != 0u) != in_contact) continue;
    response += proximity_s[f] + response_s[f];
    simulation += simulation_s[f] - proximity_s[f] - response_s[f];
  }
  return simulation > 0.0 ? response / simulation : std::numeric_limits<double>::quiet_NaN();
}

double MethodRun::total_simulation_s() const {
  return std::accumulate(simulation_s.begin(), simulation_s.end(), 0.0);
}

double MethodRun::total_collision_s() const {
  return std::accumulate(collision_s.begin(), collision_s.end(), 0.0);
}

double MethodRun::total_simulation_device_s() const {
  return std::accumulate(simulation_device_s.begin(), simulation_device_s.end(), 0.0);
}

double MethodRun::total_collision_device_s() const {
  return std::accumulate(collision_device_s.begin(), collision_device_s.end(), 0.0);
}

std::uint64_t MethodRun::pairs() const {
  return std::accumulate(contacts.begin(), contacts.end(), std::uint64_t{0});
}

StageTimes stage_times(const MethodRun& run, const std::vector<Stage>& stages) {
  StageTimes t;
  t.device_times = !run.collision_device_s.empty();
  for (std::size_t f = 0; f < stages.size() && f < run.collision_s.size(); ++f) {
    ++t.frames[stages[f]];
    t.ms_per_frame[stages[f]] += 1e3 * (run.simulation_s[f] + run.collision_s[f]);
    t.collision_ms_per_frame[stages[f]] += 1e3 * run.collision_s[f];
    if (t.device_times) {
      t.device_ms_per_frame[stages[f]] +=
          1e3 * (run.simulation_device_s[f] + run.collision_device_s[f]);
      t.collision_device_ms_per_frame[stages[f]] += 1e3 * run.collision_device_s[f];
    }
  }
  for (int s = 0; s < 3; ++s) {
    if (t.frames[s] == 0) continue;
    t.ms_per_frame[s] /= t.frames[s];
    t.collision_ms_per_frame[s] /= t.frames[s];
    t.device_ms_per_frame[s] /= t.frames[s];
    t.collision_device_ms_per_frame[s] /= t.frames[s];
  }
  return t;
}

std::vector<SceneBench> run_bench(const BenchOptions& o, const BenchProgress& progress) {
  if (o.repeat < 1) throw Error("--repeat must be at least 1");
  if (o.methods.empty()) throw Error("bench needs at least one method");
  for (BroadPhase m : o.methods) {
    if (m == BroadPhase::kNone) throw Error("'none' is not a collision method to compare");
  }
  // Frames of every measured run, for the progress display.
  long total = 0;
  std::vector<Scene> scenes;
  for (const auto& file : o.scenes) {
    progress.status("reading " + file.string());
    scenes.push_back(read_scene(file));
    const int frames = o.frames > 0 ? o.frames : scenes.back().settings.frames;
    total += static_cast<long>(frames) * o.repeat * static_cast<long>(o.methods.size()) *
             static_cast<long>(o.backends.size());
  }
  long done = 0;
  std::string what;
  const auto frame_done = [&] { progress.frame(++done, total, what); };

  std::vector<SceneBench> results;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const Scene& scene = scenes[s];
    const int frames = o.frames > 0 ? o.frames : scene.settings.frames;
    progress.status("building the bodies of " + o.scenes[s].string());
    const std::vector<BodyInit> bodies = make_scene_bodies(scene, load_scene_model, frames);
    const StepSettings settings = step_settings(scene.settings);
    for (BackendKind backend : o.backends) {
      SceneBench bench;
      bench.scene = o.scenes[s].string();
      bench.backend = std::string(backend_label(backend));
      bench.frames = frames;
      bench.repeat = o.repeat;
      WorldOptions world_options;
      world_options.backend = backend;
      world_options.cpu_threads = o.cpu_threads;
      world_options.self_collision = scene.collision.self;
      world_options.response = scene.response;
      for (BroadPhase method : o.methods) {
        what = o.scenes[s].filename().string() + " " + bench.backend + " " +
               std::string(broadphase_name(method));
        // Warm-up: shader compilation on first dispatch, caches, thread pools.
        (void)measure(
            bodies, settings, world_options, method, std::min(o.warmup_frames, frames), [] {},
            bench.device);
        std::vector<MethodRun> repeats;
        for (int r = 0; r < o.repeat; ++r) {
          repeats.push_back(
              measure(bodies, settings, world_options, method, frames, frame_done, bench.device));
        }
        std::sort(repeats.begin(), repeats.end(),
                  [](const MethodRun& x, const MethodRun& y) { return x.total_s() < y.total_s(); });
        bench.runs.push_back(std::move(repeats[repeats.size() / 2]));  // the median
      }
      bench.stages = stages_from(bench.runs.front().contacts);
      bench.device_times = bench.runs.front().collision_device_s.empty() ? DeviceTimes::kNone
                           : is_software_renderer(bench.device)          ? DeviceTimes::kCpu
                                                                         : DeviceTimes::kGpu;
      for (const MethodRun& run : bench.runs) {
        if (run.contacts != bench.runs.front().contacts) {
          bench.disagreements.emplace_back(broadphase_name(run.method));
        }
      }
      progress.measured(bench);
      results.push_back(std::move(bench));
    }
  }
  return results;
}

}  // namespace deformcd::app
