#include "refit_rows.h"

#include <algorithm>
#include <thread>
#include <vector>

#include "core/collision/collision_data.h"
#include "core/collision/vertex_positions.h"
#include "cpu/cpu_bvh_trees.h"
#include "cpu/executor.h"

namespace deformcd::bench {

void refit_row(benchmark::State& state, const ContactFrames& frames, int threads) {
  // The caller's arrays, read in place, as the detector reads them.
  FramePositions current = frames.positions.front();
  std::vector<collision::MeshVertices> views;
  for (const std::vector<glm::vec3>& mesh : current)
    views.push_back({&mesh[0].x, 3u});
  collision::CollisionData data = collision::lay_out_meshes(frames.meshes, nullptr);
  collision::build_hierarchies(data, views.data());
  cpu::Executor executor(threads);
  cpu::BvhTrees trees;
  executor.run([&] { trees.upload(data, views.data()); });
  for (auto _ : state) {
    for (const FramePositions& positions : frames.positions) {
      state.PauseTiming();
      for (std::size_t m = 0; m < current.size(); ++m)
        std::copy(positions[m].begin(), positions[m].end(), current[m].begin());
      state.ResumeTiming();
      executor.run([&] { trees.refit(views.data()); });
      benchmark::DoNotOptimize(trees.area_ratio(0));
    }
  }
  state.counters["nodes"] = static_cast<double>(trees.boxes().size());
  state.counters["threads"] =
      threads == 0 ? static_cast<double>(std::thread::hardware_concurrency()) : threads;
  state.counters["per_frame"] = benchmark::Counter(
      static_cast<double>(frames.positions.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace deformcd::bench
