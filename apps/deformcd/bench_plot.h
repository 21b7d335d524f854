#pragma once
// `bench --plot FILE.png`: a grouped bar chart like the paper's Fig. 11, drawn by gnuplot.

#include <filesystem>
#include <string>
#include <vector>

#include "bench_runner.h"

namespace deformcd::app {

/// The gnuplot script drawing `results` from `data` (bench_plot_data) into `image`: one group
/// of bars per scene and backend, one bar per method named under it, each the total run time V
/// stacked as simulation (grey) under collision detection (red), the total and the collision
/// time written on top; the legend under the plot, clear of the bars.
[[nodiscard]] std::string bench_plot_script(const std::vector<SceneBench>& results,
                                            const std::filesystem::path& data,
                                            const std::filesystem::path& image);

/// One row per bar: x, simulation s, collision s, total s, method.
[[nodiscard]] std::string bench_plot_data(const std::vector<SceneBench>& results);

/// Runs `gnuplot` (found by the caller, before the work) on the script. The PNG appears at
/// `file` only when complete; errors name `file` as given (--plot FILE).
void plot_bench(const std::vector<SceneBench>& results, const std::filesystem::path& gnuplot,
                const std::filesystem::path& file);

}  // namespace deformcd::app
