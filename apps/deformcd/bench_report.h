#pragma once
// What `deformcd bench` prints and writes: the paper's table (phase, V1, V2, I) and the detail,
// JSON and CSV.

#include <ostream>
#include <string>
#include <vector>

#include "bench_runner.h"

namespace deformcd::app {

/// The paper's improvement of a method over the baseline, I = (V1 - V2) / V2.
[[nodiscard]] inline double improvement(double v1, double v2) {
  return (v1 - v2) / v2;
}

/// One scene on one backend, printed as soon as it is measured: the summary (each method
/// against the first, the baseline), the detail per method, on a GPU the device times, the
/// contact response's share, and how the rows were measured.
void print_bench_table(std::ostream& out, const SceneBench& bench);

/// How the measurements were made, recorded with them.
struct BenchRecord {
  std::string version;    ///< deformcd's
  int repeat = 1;         ///< runs per measurement (the median is kept)
  int warmup_frames = 0;  ///< of the discarded run before each measurement
  int threads = 0;        ///< CPU backend threads
};

/// {"deformcd_version":..,"repeat":..,"warmup_frames":..,"threads":..,
///  "scenes":[{"scene":..,"backend":..,"device":..,"frames":..,"baseline":..,
///  "methods":{"brute":{"total_s":..,"simulation_s":..,"collision_s":..,
///  "ms_per_frame":{"before":..,"contact":..,"after":..},"collision_ms_per_frame":{...},
///  "frames_per_stage":{...},"pairs":..,"candidates":..,"per_frame":{"simulation_ms":[..],
///  "collision_ms":[..],"contacts":[..],"candidates":[..]}},...},
///  "improvement":{"octree":..},"speedup":{"octree":..},"collision_speedup":{...},
///  "methods_agree":..,"device_times":"none"|"gpu"|"cpu"},...]}; on GL each method also has
///  "device_simulation_s", "device_collision_s", "device_ms_per_frame",
///  "collision_device_ms_per_frame" and per_frame "simulation_device_ms",
///  "collision_device_ms" (timer queries; "cpu": a software renderer, CPU times).
[[nodiscard]] std::string bench_json(const std::vector<SceneBench>& results,
                                     const BenchRecord& record);

/// A header, then one row per scene, backend and method.
[[nodiscard]] std::string bench_csv(const std::vector<SceneBench>& results,
                                    const BenchRecord& record);

}  // namespace deformcd::app
