// `deformcd bench SCENE...`: the paper's experiment, each collision method on each backend over
// the same frames; prints the paper's table and writes JSON, CSV and a chart.

#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_plot.h"
#include "bench_report.h"
#include "bench_runner.h"
#include "commands.h"
#include "deformcd/io.h"
#include "progress.h"

namespace deformcd::app {

namespace {

struct BenchArgs {
  std::vector<std::string> scenes;
  int frames = 45;
  std::vector<std::string> backends = {"gl", "cpu"};
  std::vector<std::string> methods = {"all"};
  int repeat = 1;
  int threads = 0;
  std::string json;
  std::string csv;
  std::string plot;
};

int bench(const BenchArgs& a) {
  BenchOptions o;
  for (const std::string& s : a.scenes)
    o.scenes.emplace_back(s);
  for (const std::string& b : a.backends) {
    const BackendKind kind = parse_backend(b);
    if (kind == BackendKind::kAuto) throw Error("--backend takes gl and/or cpu, not auto");
    o.backends.push_back(kind);
  }
  for (const std::string& m : a.methods) {
    if (m == "all") {  // the baseline first, then the paper's method, then ours
      for (const std::string& name : broadphase_names())
        o.methods.push_back(parse_broadphase(name));
    } else {
      o.methods.push_back(parse_broadphase(m));
    }
  }
  if (a.frames < 1) throw Error("--frames must be at least 1");
  o.frames = a.frames;
  o.repeat = a.repeat;
  o.cpu_threads = a.threads;

  std::unique_ptr<Progress> bar;
  const std::vector<SceneBench> results = run_bench(o, [&](long done, long total) {
    if (!bar) bar = std::make_unique<Progress>("benchmarking", total);
    bar->update(done);
  });
  if (bar) bar->done();

  print_bench_table(std::cout, results);
  std::cout << "\nTimes: wall clock around each stage after waiting for the backend (glFinish "
               "on GL, no timer queries); warm-up runs excluded"
            << (a.repeat > 1 ? "; the median of the repeats" : "") << ".\n";
  if (!a.json.empty()) {
    write_file_atomically(a.json, bench_json(results));
    std::cout << "json       " << a.json << '\n';
  }
  if (!a.csv.empty()) {
    write_file_atomically(a.csv, bench_csv(results));
    std::cout << "csv        " << a.csv << '\n';
  }
  if (!a.plot.empty()) {
    plot_bench(results, a.plot);
    std::cout << "plot       " << a.plot << '\n';
  }
  for (const SceneBench& b : results) {
    if (!b.disagreements.empty()) {
      std::cerr << "deformcd: error: the methods found different contacts on " << b.scene << " ("
                << b.backend << ")\n";
      return 1;
    }
  }
  return 0;
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
                  "Frames per run: the scene's whole trajectory in this many (4500 in the "
                  "paper)")
      ->capture_default_str();
  cmd->add_option("--backend", a->backends, "Backends, comma-separated: gl, cpu")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--methods", a->methods,
                  "Broad phases, comma-separated (brute, octree, octree-compact, bvh, or all); "
                  "the first is the baseline V1")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--repeat", a->repeat, "Runs per measurement; the median is reported")
      ->capture_default_str();
  cmd->add_option("--threads", a->threads, "CPU backend threads (0: all cores)");
  cmd->add_option("--json", a->json, "Write the results as JSON");
  cmd->add_option("--csv", a->csv, "Write the results as CSV");
  cmd->add_option("--plot", a->plot, "Draw a bar chart (PNG, with gnuplot)");
  return [a]() { return bench(*a); };
}

}  // namespace deformcd::app
