#include "bench_plot.h"

#include "deformcd/io.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <system_error>

#include "deformcd/error.h"

extern char** environ;

namespace deformcd::app {

namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Bars of one group sit one unit apart; groups are separated by one empty slot.
double bar_x(std::size_t group, std::size_t methods, std::size_t method) {
  return static_cast<double>(group * (methods + 1) + method);
}

std::string group_label(const SceneBench& b) {
  return fs::path(b.scene).stem().string() + ", " + b.backend + ", " + std::to_string(b.frames) +
         " frames";
}

void write_text(const fs::path& file, const std::string& text, const fs::path& target) {
  std::ofstream out(file);
  out << text;
  if (!out.flush()) {
    throw Error("--plot " + target.string() + ": cannot write gnuplot's input " + file.string());
  }
}

// A private directory for gnuplot's input, removed with everything in it.
struct ScratchDirectory {
  fs::path path;
  explicit ScratchDirectory(const fs::path& target) {
    std::string pattern = (fs::temp_directory_path() / "deformcd-plot-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw Error("--plot " + target.string() + ": cannot create a temporary directory in " +
                  fs::temp_directory_path().string());
    }
    path = pattern;
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
};

int run_program(const fs::path& program, const fs::path& argument) {
  std::string arg0 = program.string();
  std::string arg1 = argument.string();
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  if (posix_spawn(&pid, arg0.c_str(), nullptr, nullptr, argv, environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

std::string bench_plot_data(const std::vector<SceneBench>& results) {
  std::ostringstream out;
  out.precision(9);
  const std::size_t methods = results.front().runs.size();
  for (std::size_t g = 0; g < results.size(); ++g) {
    for (std::size_t m = 0; m < results[g].runs.size(); ++m) {
      const MethodRun& r = results[g].runs[m];
      out << bar_x(g, methods, m) << ' ' << r.total_simulation_s() << ' ' << r.total_collision_s()
          << ' ' << r.total_s() << " \"" << broadphase_name(r.method) << "\"\n";
    }
  }
  return out.str();
}

std::string bench_plot_script(const std::vector<SceneBench>& results, const fs::path& data,
                              const fs::path& image) {
  const std::size_t methods = results.front().runs.size();
  const double width = static_cast<double>(results.size() * (methods + 1));
  std::ostringstream s;
  const int pixels = std::max(640, std::min(1600, static_cast<int>(110 * width)));
  s << "set terminal pngcairo size " << pixels << ",600 noenhanced font 'sans,12'\n"
    << "set output " << quoted(image.string()) << "\n"
    << "set title 'Total run time V per collision method (simulation + collision detection)'\n"
    << "set ylabel 'V (s)'\nset yrange [0:*]\nset offsets 0, 0, graph 0.16, 0\n"
    << "set grid ytics\nset border 3\nset tics nomirror\n"
    << "set key outside bottom center horizontal samplen 2 width 2\n"
    << "set style fill solid 0.9 border rgb '#333333'\nset boxwidth 0.7\n"
    << "set xrange [-0.75:" << width - 1.25 << "]\n"
    << "set bmargin 6\n";
  // Each group's name under its methods' names.
  for (std::size_t g = 0; g < results.size(); ++g) {
    const double centre = bar_x(g, methods, 0) + 0.5 * static_cast<double>(methods - 1);
    s << "set label " << g + 1 << " " << quoted(group_label(results[g])) << " at " << centre
      << ", graph 0 center offset 0,-2.6 font 'sans,12:Bold'\n";
  }
  // The full height (simulation + collision) in red, the simulation part over it in grey, then
  // the total and the collision time above each bar.
  s << "plot " << quoted(data.string())
    << " using 1:4:xtic(5) with boxes lc rgb '#c0392b' title 'collision detection', \\\n"
    << "  '' using 1:2 with boxes lc rgb '#b3b6b7' title 'simulation', \\\n"
    << "  '' using 1:4:(sprintf('%.3g s\\nCD %.3g s', $4, $3)) with labels center offset 0,1.6 "
       "font 'sans,10' "
       "notitle\n";
  return s.str();
}

void plot_bench(const std::vector<SceneBench>& results, const fs::path& gnuplot,
                const fs::path& file) {
  if (results.empty()) throw Error("--plot " + file.string() + ": nothing to plot");
  const ScratchDirectory scratch(file);
  const fs::path data = scratch.path / "bench.dat";
  const fs::path commands = scratch.path / "bench.gp";
  // gnuplot writes the chart into an unnamed temporary next to the target, named only once
  // gnuplot succeeded: a failure, or a kill of either process, leaves no partial chart.
  StreamedFileWriter out(file);
  const fs::path image = out.path_for_child_process();
  write_text(data, bench_plot_data(results), file);
  write_text(commands, bench_plot_script(results, data, image), file);
  const int status = run_program(gnuplot, commands);
  if (status != 0) {
    throw Error("--plot " + file.string() + ": gnuplot (" + gnuplot.string() + ") failed" +
                (status > 0 ? " with exit status " + std::to_string(status) : std::string()) +
                "; its message is above");
  }
  out.commit();
}

}  // namespace deformcd::app
