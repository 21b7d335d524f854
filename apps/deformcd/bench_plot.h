#pragma once
// `bench --plot FILE.png`: a grouped bar chart like the paper's Fig. 11, drawn by gnuplot.

#include <filesystem>
#include <vector>

#include "bench_runner.h"

namespace deformcd::app {

/// One group of bars per scene and backend, one bar per method: the total run time V, split
/// into simulation and collision detection (stacked). Runs `gnuplot` (Debian: gnuplot-nox);
/// throws Error when it is missing or fails. The PNG appears at `file` only when complete.
void plot_bench(const std::vector<SceneBench>& results, const std::filesystem::path& file);

}  // namespace deformcd::app
