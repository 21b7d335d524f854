#include "bench_plot.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "deformcd/error.h"

namespace deformcd::app {

namespace {

namespace fs = std::filesystem;

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string shell_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s)
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// One row per (scene, backend): label, then simulation and collision seconds per method.
std::string data_rows(const std::vector<SceneBench>& results) {
  std::ostringstream out;
  for (const SceneBench& b : results) {
    out << '"' << fs::path(b.scene).stem().string() << " (" << b.backend << ")\"";
    for (const MethodRun& r : b.runs)
      out << ' ' << r.total_simulation_s() << ' ' << r.total_collision_s();
    out << '\n';
  }
  return out.str();
}

// Each method's bars sit side by side in a group (one group per scene and backend), each bar
// stacked: simulation below, collision detection above. gnuplot's "rowstacked" histograms do
// not cluster, so the bars are drawn as boxes at computed x positions.
std::string script(const std::vector<SceneBench>& results, const fs::path& data,
                   const fs::path& output) {
  const std::size_t methods = results.front().runs.size();
  const double width = 0.8 / static_cast<double>(methods);
  std::ostringstream s;
  s << "set terminal pngcairo size 1000,560 noenhanced font 'sans,10'\n"
    << "set output " << quoted(output.string()) << "\n"
    << "set title 'Total run time V per method and scene: simulation + collision detection'\n"
    << "set ylabel 'V (s)'\nset yrange [0:*]\nset grid ytics\nset key top left\n"
    << "set style fill solid 0.85 border -1\nset boxwidth " << width << "\n"
    << "set xtics nomirror\nset xrange [-0.6:" << static_cast<double>(results.size()) - 0.4
    << "]\n";
  // Per method: a dark colour (collision detection, on top) and a light one (simulation).
  const char* dark[] = {"#a93226", "#1f618d", "#1e8449", "#6c3483", "#b9770e", "#424949"};
  const char* light[] = {"#f1948a", "#85c1e9", "#82e0aa", "#c39bd3", "#f8c471", "#aab7b8"};
  s << "plot " << quoted(data.string()) << " using 0:(NaN):xtic(1) notitle";
  for (std::size_t m = 0; m < methods; ++m) {
    const double offset = (static_cast<double>(m) - 0.5 * static_cast<double>(methods - 1)) * width;
    const std::size_t sim_col = 2 + 2 * m;
    const std::size_t cd_col = sim_col + 1;
    const std::string name(broadphase_name(results.front().runs[m].method));
    // The full height (simulation + collision) in the dark colour, then the simulation part
    // over it in the light one.
    s << ", '' using ($0+" << offset << "):($" << sim_col << "+$" << cd_col
      << ") with boxes lc rgb '" << dark[m % 6] << "' title " << quoted(name + ": collision")
      << ", '' using ($0+" << offset << "):" << sim_col << " with boxes lc rgb '" << light[m % 6]
      << "' title " << quoted(name + ": simulation");
  }
  s << "\n";
  return s.str();
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out.flush()) throw Error("cannot write " + file.string());
}

}  // namespace

void plot_bench(const std::vector<SceneBench>& results, const fs::path& file) {
  if (results.empty()) throw Error("nothing to plot");
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  const std::string stem = "." + file.filename().string() + ".tmp-" + std::to_string(getpid());
  const fs::path data = dir / (stem + ".dat");
  const fs::path commands = dir / (stem + ".gp");
  const fs::path image = dir / (stem + ".png");
  struct Cleanup {
    std::vector<fs::path> files;
    ~Cleanup() {
      std::error_code ignored;
      for (const fs::path& f : files)
        fs::remove(f, ignored);
    }
  } cleanup{{data, commands, image}};
  write_text(data, data_rows(results));
  write_text(commands, script(results, data, image));
  const std::string command = "gnuplot " + shell_quoted(commands.string()) + " 2>&1";
  const int status = std::system(command.c_str());
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const bool missing = WIFEXITED(status) && WEXITSTATUS(status) == 127;
    throw Error("cannot draw " + file.string() + ": " +
                (missing ? std::string("gnuplot is not installed (Debian: apt-get install "
                                       "gnuplot-nox; scripts/install_deps.sh installs it)")
                         : std::string("gnuplot failed (see its message above)")));
  }
  std::error_code ec;
  fs::rename(image, file, ec);
  if (ec) throw Error("cannot write " + file.string() + ": " + ec.message());
}

}  // namespace deformcd::app
