// The deformcd tool as a user runs it: exit codes, messages, and no partial output on failure.

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "deformcd/io.h"
#include "support/mesh_fixtures.h"

#include "support/cli_runner.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace {

using deformcd::test::CliRun;
using deformcd::test::run_cli;

class CliTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
  }
  // A scene of one falling cube (TetGen files next to it).
  std::string cube_scene() const {
    deformcd::write_tetgen(deformcd::test::unit_cube(), path("cube"));
    write("cube.json", R"({"settings": {"frames": 4}, "bodies": [{"model": "cube"}]})");
    return path("cube.json");
  }
  static std::string lines_of(const std::string& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  // What `bench` (CPU, bvh, 3 frames) says of two cubes with contact response, the second at
  // `x` along x, under scene settings `settings`: its run, and its JSON without blanks.
  struct BenchOfCubes {
    CliRun run;
    std::string json;
  };
  BenchOfCubes bench_two_cubes(const std::string& settings, float x) const {
    deformcd::write_tetgen(deformcd::test::unit_cube(), path("cube"));
    write("two.json", R"({"settings": )" + settings + R"(, "response": {},
                          "bodies": [{"model": "cube"},
                                     {"model": "cube", "position": [)" +
                          std::to_string(x) + ", 0, 0]}]}");
    BenchOfCubes b{run_cli("bench " + path("two.json") +
                           " --backend cpu --methods bvh --frames 3 --json " + path("bench.json")),
                   lines_of(path("bench.json"))};
    std::erase_if(b.json, [](char c) { return c == ' ' || c == '\n'; });
    return b;
  }
  deformcd::test::TempDir dir_;
};

TEST_F(CliTest, InfoJsonReportsCounts) {
  deformcd::TetMesh cube = deformcd::test::unit_cube();
  deformcd::write_tetgen(cube, path("cube"));
  const CliRun r = run_cli("info " + path("cube") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"nodes\": 8"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"tetrahedra\": 5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"faces\": 12"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"springs\": 30"), std::string::npos) << r.output;
}

TEST_F(CliTest, InfoOnMissingFileNamesIt) {
  const CliRun r = run_cli("info " + path("nothing_here"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("nothing_here"), std::string::npos) << r.output;
}

TEST_F(CliTest, InfoOnMalformedNodeFileNamesFileAndLine) {
  write("bad.node", "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 x 0\n3 0 0 1\n");
  write("bad.ele", "1 4 0\n0 0 1 2 3\n");
  const CliRun r = run_cli("info " + path("bad"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.node:4"), std::string::npos) << r.output;
}

TEST_F(CliTest, UnknownOptionIsAUsageError) {
  const CliRun r = run_cli("info --no-such-flag");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("no-such-flag"), std::string::npos) << r.output;
}

TEST_F(CliTest, AnUnknownCommandIsNamed) {
  const CliRun r = run_cli("foo");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("unknown command 'foo' (commands: info, tetra, run, bench"),
            std::string::npos)
      << r.output;
}

TEST_F(CliTest, EveryUsageErrorExitsWithStatus2AndNamesTheCommand) {
  const std::string scene = cube_scene();
  for (const std::string& args : std::vector<std::string>{
           "run", "run " + scene + " --frames 0", "run " + scene + " --backend quantum",
           "run " + scene + " --threads -1", "run " + scene + " --every-frame",
           "bench " + scene + " --repeat 0", "bench " + scene + " --methods brute,kd",
           "tetra x.off", "info --json --json-please"}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    const std::string command = "deformcd " + args.substr(0, args.find(' ')) + ": error: ";
    EXPECT_NE(r.output.find(command), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--help"), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_EQ(run_cli("run --help").status, 0);
  EXPECT_EQ(run_cli("--version").status, 0);
}

TEST_F(CliTest, RunCountsItsBodiesInGoodEnglishAndSaysWhatItDoesAtOnce) {
  const CliRun r = run_cli("run " + cube_scene() + " --backend cpu");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("(1 body, 8 nodes)"), std::string::npos) << r.output;
  // Status lines before the work, in order.
  const std::size_t reading = r.output.find("deformcd: reading ");
  const std::size_t building = r.output.find("deformcd: building 1 body\n");
  const std::size_t starting = r.output.find("deformcd: starting the cpu backend");
  ASSERT_NE(reading, std::string::npos) << r.output;
  EXPECT_LT(reading, building) << r.output;
  EXPECT_LT(building, starting) << r.output;
}

TEST_F(CliTest, RunWritesThePositionsOfTheLastOrOfEveryFrame) {
  const std::string scene = cube_scene();
  CliRun r = run_cli("run " + scene + " --backend cpu --frames 3 --positions " + path("last.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string last = lines_of(path("last.json"));
  EXPECT_EQ(last.rfind("{\"bodies\":[{\"name\":\"cube\",\"positions\":[[", 0), 0u) << last;
  EXPECT_NE(last.find("\"frame\":3}\n"), std::string::npos) << last;
  EXPECT_EQ(std::count(last.begin(), last.end(), '\n'), 1);

  r = run_cli("run " + scene + " --backend cpu --frames 3 --every-frame --positions " +
              path("all.jsonl"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::istringstream all(lines_of(path("all.jsonl")));
  int frame = 0;
  for (std::string line; std::getline(all, line); ++frame) {
    EXPECT_NE(line.find("\"frame\":" + std::to_string(frame) + "}"), std::string::npos) << line;
  }
  EXPECT_EQ(frame, 4);  // frames 0..3
  std::istringstream lines(lines_of(path("all.jsonl")));
  std::string line;
  for (int f = 0; f <= 3; ++f)
    std::getline(lines, line);
  EXPECT_EQ(line + "\n", last);  // the last line is the file without --every-frame
}

// With a scene's `response`, bench reports the response's stages, its searches and widenings a
// frame, its iterations a substep and the constraints each frame ended with: two cubes falling
// side by side, never near, one search a frame, no widening, each cube searched against itself
// once (self-contact is on by default with a response; falling as a whole, its pairs are kept),
// the 8 iterations asked for and no constraint (a cube's faces are never near each other).
TEST_F(CliTest, BenchReportsTheResponsesSearchesAndWidenings) {
  const auto [r, json] = bench_two_cubes(R"({"frames": 3})", 3.0f);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(
      r.output.find("x the simulation); searches 1.00, widenings 0.00, bodies searched against "
                    "themselves 0.67 a frame; iterations 8.00 a substep"),
      std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("no frame ended with constraints between bodies"), std::string::npos)
      << r.output;
  EXPECT_NE(json.find("\"searches\":[1,1,1]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"widenings\":[0,0,0]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"constraints\":[0,0,0]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"constraints_between\":[0,0,0]"), std::string::npos) << json;
}

// Cubes that start closer than the contact thickness end every frame with constraints, and bench
// reports the response's cost over those frames.
TEST_F(CliTest, BenchSplitsTheResponsesCostByFramesWithConstraints) {
  const auto [r, json] = bench_two_cubes(R"({"frames": 3, "gravity": [0, 0, 0]})", 1.05f);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("the 3 frames ending with constraints between bodies: proximity + "
                          "response = "),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("; the other"), std::string::npos) << r.output;
  EXPECT_EQ(json.find("\"constraints\":[0"), std::string::npos) << json;
  EXPECT_EQ(json.find("\"constraints_between\":[0"), std::string::npos) << json;
  EXPECT_NE(json.find("\"constraints\":["), std::string::npos) << json;
}

TEST_F(CliTest, OutputPathsAreCheckedBeforeAnyWorkAndNamedAsGiven) {
  const std::string scene = cube_scene();
  std::ofstream(path("a_file")) << "in the way";
  const std::string missing = path("no_such_dir/out.json");
  const std::string under_a_file = path("a_file/out.json");
  for (const std::string& args :
       std::vector<std::string>{"run " + scene + " --positions " + missing,
                                "run " + scene + " --contacts " + under_a_file,
                                "bench " + scene + " --backend cpu --json " + missing,
                                "bench " + scene + " --backend cpu --csv " + under_a_file,
                                "bench " + scene + " --backend cpu --plot " + missing,
                                "bench " + scene + " --backend cpu --plot " + path("."),
                                "tetra " + path("x.off") + " -o " + path("no_such_dir/x")}) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    const std::string given = args.substr(args.rfind(' ') + 1);
    EXPECT_NE(r.output.find(given), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("deformcd: reading"), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(path("no_such_dir")));
}

TEST_F(CliTest, APlotWithoutGnuplotFailsBeforeAnyWork) {
  fs::create_directories(path("empty_bin"));
  const CliRun r = run_cli("bench " + cube_scene() + " --backend cpu --plot " + path("chart.png"),
                           "PATH=" + path("empty_bin"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--plot " + path("chart.png") + ": needs gnuplot"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("PATH"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("deformcd: reading"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("chart.png")));
}

#ifdef DEFORMCD_HAS_TETGEN
TEST_F(CliTest, TetraWritesAMeshThatInfoReads) {
  deformcd::write_off(deformcd::test::sphere(2), path("ball.off"));
  CliRun r = run_cli("tetra " + path("ball.off") + " -o " + path("ball") +
                     " --preserve-surface --quality 1.4");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* ext : {".node", ".ele", ".face"})
    EXPECT_TRUE(fs::exists(path("ball") + ext));
  r = run_cli("info " + path("ball") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"faces\": 128"), std::string::npos) << r.output;
  // A surface file given directly is tetrahedralized on the fly.
  r = run_cli("info " + path("ball.off") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"faces\": 128"), std::string::npos) << r.output;
}

TEST_F(CliTest, TetraOnOpenSurfaceFailsAndWritesNothing) {
  deformcd::SurfaceMesh open = deformcd::test::sphere(1);
  open.triangles.pop_back();
  deformcd::write_off(open, path("open.off"));
  const CliRun r = run_cli("tetra " + path("open.off") + " -o " + path("out"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("open.off"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("boundary edge"), std::string::npos) << r.output;
  for (const auto& entry : fs::directory_iterator(dir_.path())) {
    EXPECT_EQ(entry.path().filename(), "open.off") << "left behind: " << entry.path();
  }
}

TEST_F(CliTest, TetraOnSelfIntersectingSurfaceFailsCleanly) {
  deformcd::SurfaceMesh both = deformcd::test::octahedron();
  const deformcd::SurfaceMesh second = deformcd::test::octahedron();
  for (const auto& v : second.vertices)
    both.vertices.push_back(v + glm::dvec3(0.5, 0.3, 0.2));
  for (const auto& t : second.triangles)
    both.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
  deformcd::write_off(both, path("twice.off"));
  const CliRun r = run_cli("tetra " + path("twice.off") + " -o " + path("out"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("intersects itself"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.node")));
}
#endif

#ifdef DEFORMCD_HAS_GL
TEST_F(CliTest, GpuInfoReportsAtLeastGl43OrSaysWhy) {
  const CliRun r = run_cli("info --gpu");
  if (r.status != 0) {
    // Without GL 4.3 the tool must say so and point to the CPU backend.
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("CPU backend"), std::string::npos) << r.output;
    return;
  }
  EXPECT_NE(r.output.find("GL version"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max SSBO size"), std::string::npos) << r.output;
}
#endif

}  // namespace
