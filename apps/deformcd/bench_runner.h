#pragma once
// `deformcd bench`: runs each scene with each collision method on each backend over the same
// frames and measures the simulation and the collision stage of every frame: wall clock (after
// waiting for the backend, glFinish on GL) and, on GL, device time from timer queries.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "deformcd/collision.h"
#include "deformcd/intersection_census.h"
#include "deformcd/world.h"

namespace deformcd::app {

/// The paper's three phases of a run, from the contacts found: before the first frame with a
/// contact, from it to the last, and after.
enum Stage { kBefore = 0, kContact = 1, kAfter = 2 };
inline constexpr std::array<const char*, 3> kStageNames = {"before", "contact", "after"};

/// One method's measured run (the median of the repeats, by total time).
struct MethodRun {
  BroadPhase method = BroadPhase::kBrute;
  std::vector<double> simulation_s;     ///< per frame 1..N
  std::vector<double> collision_s;      ///< per frame 1..N
  std::vector<std::uint64_t> contacts;  ///< per frame 1..N
  /// Per frame 1..N: face pairs given to the triangle test.
  std::vector<std::uint64_t> candidates;
  /// Per frame 1..N on GL: the stages' device time from timer queries (GL_TIME_ELAPSED).
  /// Empty on the CPU.
  std::vector<double> simulation_device_s;
  std::vector<double> collision_device_s;
  /// Per frame 1..N with contact response (a scene's `response`): the proximity searches and
  /// the projections, included in simulation_s (the stage step() runs). Empty without.
  std::vector<double> proximity_s;
  std::vector<double> response_s;
  /// Per frame 1..N with contact response: the proximity searches, the widenings around
  /// nodes that strayed and the bodies searched against themselves (World::response_counts()).
  /// Empty without.
  std::vector<std::uint64_t> searches;
  std::vector<std::uint64_t> widenings;
  std::vector<std::uint64_t> self_searches;
  std::vector<std::uint64_t> substeps;    // per frame, the response's (ResponseCounts::substeps)
  std::vector<std::uint64_t> iterations;  // per frame, ResponseCounts::iterations
  std::vector<std::uint64_t> asleep;      // per frame, the bodies asleep after it
  /// Per frame 1..N with contact response: the contact constraints the frame ended with
  /// (ResponseCounts::contact_constraints(): proximity pairs, untangling, penetrating
  /// vertices). Empty without.
  std::vector<std::uint64_t> constraints;
  /// Of those, the constraints between two different bodies (ResponseCounts::between_bodies):
  /// the frames in contact are the frames with some, since with self-contact every frame has
  /// constraints of each body with itself.
  std::vector<std::uint64_t> constraints_between;
  /// Per frame 1..N with contact response: the intersection census and the tetrahedra turned
  /// inside out (bench_intersections.h).
  std::vector<IntersectionCensus> intersections;
  std::vector<std::uint64_t> inverted_tetrahedra;

  [[nodiscard]] double total_simulation_s() const;
  [[nodiscard]] double total_collision_s() const;
  [[nodiscard]] double total_simulation_device_s() const;
  [[nodiscard]] double total_collision_device_s() const;
  [[nodiscard]] double total_proximity_s() const;
  [[nodiscard]] double total_response_s() const;
  /// The response's cost (proximity + response) over the simulation's alone (the simulation
  /// stage less both), over the frames that ended in contact, with constraints between two
  /// bodies (`in_contact` true), or the others. NaN when no frame is of that kind.
  [[nodiscard]] double response_ratio(bool in_contact) const;
  /// The paper's V: the run's total time, simulation and collision detection.
  [[nodiscard]] double total_s() const { return total_simulation_s() + total_collision_s(); }
  [[nodiscard]] std::uint64_t pairs() const;
};

/// Per-stage means of one run, given the stage of each frame.
struct StageTimes {
  std::array<int, 3> frames{};
  std::array<double, 3> ms_per_frame{};                   ///< simulation + collision
  std::array<double, 3> collision_ms_per_frame{};         ///< collision only
  bool device_times = false;                              ///< the two below are measured (GL)
  std::array<double, 3> device_ms_per_frame{};            ///< timer queries: simulation + collision
  std::array<double, 3> collision_device_ms_per_frame{};  ///< timer queries: collision only
};
[[nodiscard]] StageTimes stage_times(const MethodRun& run, const std::vector<Stage>& stages);

/// What the timer queries of a run measured: nothing (CPU backend), a GPU, or the CPU's cores
/// running a software rasterizer (llvmpipe...), whose "device" times are CPU times.
enum class DeviceTimes { kNone, kGpu, kCpu };

/// One scene on one backend, every method over the same frames.
struct SceneBench {
  std::string scene;  ///< the scene file as given
  std::string backend;
  std::string device;
  int frames = 0;
  int repeat = 1;               ///< runs per measurement, the median kept
  std::vector<MethodRun> runs;  ///< in the order of the methods asked for
  std::vector<Stage> stages;    ///< per frame, from the first run's contacts
  DeviceTimes device_times = DeviceTimes::kNone;
  /// Methods whose contact counts differ from the first method's on some frame (empty: all
  /// agree, as they must).
  std::vector<std::string> disagreements;
};

struct BenchOptions {
  std::vector<std::filesystem::path> scenes;
  std::vector<BackendKind> backends;
  std::vector<BroadPhase> methods;
  int frames = 0;  ///< the trajectory in this many frames; 0: the scene's own
  int repeat = 1;
  int warmup_frames = 2;  ///< a discarded short run per backend and method, before measuring
  int cpu_threads = 0;
};

/// What run_bench reports as it goes.
struct BenchProgress {
  /// Before a step that takes time outside the measured frames ("reading a.json").
  std::function<void(const std::string& text)> status = [](const std::string&) {};
  /// After each measured frame: frames done and frames in all runs, and what is measured
  /// ("phase1.json cpu bvh").
  std::function<void(long done, long total, const std::string& what)> frame =
      [](long, long, const std::string&) {};
  /// When a scene's runs on one backend are all measured, before the next backend's begin.
  std::function<void(const SceneBench& bench)> measured = [](const SceneBench&) {};
};

/// Runs everything. Throws Error/GlError (e.g. kGl without GL 4.3, naming the scene).
[[nodiscard]] std::vector<SceneBench> run_bench(const BenchOptions& options,
                                                const BenchProgress& progress);

}  // namespace deformcd::app
