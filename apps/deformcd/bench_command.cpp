// `deformcd bench SCENE...`: the paper's experiment, each collision method on each backend over
// the same frames; prints the paper's table and writes JSON, CSV and a chart.

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_plot.h"
#include "bench_report.h"
#include "bench_runner.h"
#include "commands.h"
#include "deformcd/backend.h"
#include "deformcd/io.h"
#include "option_values.h"
#include "output_paths.h"
#include "progress.h"
#include "usage_error.h"

namespace deformcd::app {

namespace {

struct BenchArgs {
  std::vector<std::string> scenes;
  int frames = 45;
  std::vector<std::string> backends = {"auto"};
  std::vector<std::string> methods = {"all"};
  int repeat = 1;
  int threads = 0;
  std::string json;
  std::string csv;
  std::string plot;
};

// The command line as options for the runner; every mistake is a UsageError, found before any
// work.
BenchOptions bench_options(const BenchArgs& a) {
  BenchOptions o;
  for (const std::string& s : a.scenes)
    o.scenes.emplace_back(s);
  for (const std::string& b : a.backends) {
    if (b != "gl" && b != "cpu" && b != "auto") {
      throw UsageError(
          "--backend takes auto, or gl and/or cpu (each is measured and named in the "
          "results), not '" +
          b + "'");
    }
    if (b == "auto" && a.backends.size() > 1) {
      throw UsageError(
          "--backend auto chooses the backends itself: give it alone, or gl and/or cpu");
    }
    if (b != "auto") o.backends.push_back(parse_backend(b));
  }
  const std::vector<std::string>& known = broadphase_names();
  for (const std::string& m : a.methods) {
    if (m == "all") {  // the baseline first, then the paper's method, then ours
      for (const std::string& name : known)
        o.methods.push_back(parse_broadphase(name));
    } else if (std::find(known.begin(), known.end(), m) != known.end()) {
      o.methods.push_back(parse_broadphase(m));
    } else {
      std::string list;
      for (const std::string& name : known)
        list += ", " + name;
      throw UsageError("--methods: '" + m + "' is not a collision method to compare (valid: all" +
                       list + ")");
    }
  }
  check_at_least("--frames", a.frames, 1);
  check_at_least("--repeat", a.repeat, 1);
  check_threads_option(a.threads);
  o.frames = a.frames;
  o.repeat = a.repeat;
  o.cpu_threads = a.threads;
  return o;
}

// --backend auto follows the library's rule (BackendKind::kAuto): both backends on a hardware GL
// device, else the CPU alone, as `run` would choose, saying why.
std::vector<BackendKind> auto_backends() {
  const AutoBackend choice = choose_auto_backend();
  if (choice.kind == BackendKind::kGl) return {BackendKind::kGl, BackendKind::kCpu};
  std::cerr << "deformcd: bench measures the CPU backend only: " << choice.reason
            << "; --backend gl,cpu measures both\n";
  return {BackendKind::kCpu};
}

int bench(const BenchArgs& a) {
  BenchOptions o = bench_options(a);
  if (!a.json.empty()) check_output_file("--json", a.json);
  if (!a.csv.empty()) check_output_file("--csv", a.csv);
  const SummaryOnStderr summary_on_stderr(writes_stdout({a.json, a.csv, a.plot}));
  std::optional<std::filesystem::path> gnuplot;
  if (!a.plot.empty()) {
    check_output_file("--plot", a.plot);
    gnuplot = require_program("--plot", a.plot, "gnuplot",
                              "Debian: apt-get install gnuplot-nox; scripts/install_deps.sh "
                              "installs it");
  }

  if (o.backends.empty()) o.backends = auto_backends();

  std::unique_ptr<Progress> bar;
  BenchProgress progress;
  progress.status = [&](const std::string& text) {
    if (bar) bar->clear();
    status(text);
  };
  progress.frame = [&](long done, long total, const std::string& what) {
    if (!bar) bar = std::make_unique<Progress>("benchmarking", total);
    bar->set_label(what);
    bar->update(done);
  };
  // Each backend's tables as soon as they are measured, not all at the end.
  progress.measured = [&](const SceneBench& measured) {
    if (bar) bar->clear();
    print_bench_table(std::cout, measured);
    std::cout.flush();
  };
  const std::vector<SceneBench> results = run_bench(o, progress);
  if (bar) bar->done();

  BenchRecord record;
  record.version = DEFORMCD_VERSION;
  record.repeat = o.repeat;
  record.warmup_frames = o.warmup_frames;
  record.threads =
      o.cpu_threads > 0 ? o.cpu_threads : static_cast<int>(std::thread::hardware_concurrency());
  std::cout << '\n';
  if (!a.json.empty()) {
    write_file_atomically(a.json, bench_json(results, record));
    std::cout << "json       " << a.json << '\n';
  }
  if (!a.csv.empty()) {
    write_file_atomically(a.csv, bench_csv(results, record));
    std::cout << "csv        " << a.csv << '\n';
  }
  if (gnuplot) {
    plot_bench(results, *gnuplot, a.plot);
    std::cout << "plot       " << a.plot << '\n';
  }
  for (const SceneBench& b : results) {
    if (!b.disagreements.empty()) {
      std::cerr << "deformcd: error: the methods found different contacts on " << b.scene << " ("
                << b.backend << ")\n";
      return kExitFailure;
    }
  }
  return kExitOk;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto a = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Time each collision method on each backend over the same frames (the paper's "
      "experiment)");
  cmd->add_option("scenes", a->scenes, "Scene files (JSON)")->required();
  cmd->add_option("--frames", a->frames,
                  "Length of each run in frames: the scene's whole trajectory in this many "
                  "(4500 in the paper)")
      ->capture_default_str();
  cmd->add_option("--backend", a->backends,
                  "Backends, comma-separated: gl, cpu; or auto: both on a hardware GL device, "
                  "else the CPU alone (as run's auto chooses)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--methods", a->methods,
                  "Broad phases, comma-separated (brute, octree, octree-compact, bvh, or all); "
                  "the first is the baseline V1")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Runs per measurement; the median is reported")
      ->capture_default_str();
  cmd->add_option("--threads", a->threads, "CPU backend threads (0: all cores)")
      ->capture_default_str();
  cmd->add_option("--json", a->json, "Write the results as JSON");
  cmd->add_option("--csv", a->csv, "Write the results as CSV");
  cmd->add_option("--plot", a->plot, "Draw a bar chart (PNG, with gnuplot)");
  return [a]() { return bench(*a); };
}

}  // namespace deformcd::app
