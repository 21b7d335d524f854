// Issue 34: deformcd at its edges with the system, as a user meets them: outputs pointed at
// standard output, devices and pipes; thread counts; exit statuses; the auto backend's probe.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/sanitizers.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace {

using deformcd::test::CliRun;
using deformcd::test::run_cli;
using deformcd::test::run_shell;

const std::string kData = std::string(DEFORMCD_SOURCE_DIR) + "/tests/data/io/";
const std::string kCollide =
    "collide " + kData + "cube.off " + kData + "octahedron.stl --backend cpu";

struct SplitRun {
  int status = -1;
  std::string out;  // standard output alone
  std::string err;  // standard error alone
};

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `prefix deformcd args | cat` (stdout a pipe, as in a shell pipeline), with standard
// output and standard error kept apart.
SplitRun run_split(const deformcd::test::TempDir& dir, const std::string& args,
                   const std::string& prefix = "") {
  const fs::path out = dir / "stdout.txt";
  const fs::path err = dir / "stderr.txt";
  const std::string command = "cd " + std::string(DEFORMCD_SOURCE_DIR) + " && (" + prefix + " " +
                              DEFORMCD_CLI + " " + args + " 2>" + err.string() + "; echo $? >" +
                              (dir / "status").string() + ") | cat >" + out.string();
  (void)run_shell(command);
  SplitRun r;
  r.out = read_all(out);
  r.err = read_all(err);
  r.status = std::stoi(read_all(dir / "status"));
  return r;
}

// Runs the tool as user nobody (setpriv), where root is not: without setpriv, or not root, the
// command runs as is.
std::string as_nobody() {
  if (::geteuid() != 0 || !fs::exists("/usr/bin/setpriv")) return "";
  return "setpriv --reuid=nobody --regid=nogroup --clear-groups";
}

TEST(HardeningCli, DashWritesTheJsonToStandardOutputAndTheSummaryToStandardError) {
  deformcd::test::TempDir dir;
  const SplitRun r = run_split(dir, kCollide + " --json -");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // the JSON alone
  EXPECT_GT(j.at("contacts").size(), 10u);
  EXPECT_NE(r.err.find("intersecting triangle pairs"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(DEFORMCD_SOURCE_DIR) / "-"));
}

TEST(HardeningCli, RunWritesItsContactsAndPositionsToStandardOutput) {
  deformcd::test::TempDir dir;
  const SplitRun r = run_split(dir, "run scenes/phase2.json --backend cpu --frames 2 --contacts -");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count)
    EXPECT_EQ(nlohmann::json::parse(line).at("frame"), count);
  EXPECT_EQ(count, 3);  // frames 0..2
  EXPECT_NE(r.err.find("scene "), std::string::npos) << r.err;
}

TEST(HardeningCli, BenchDrawsItsChartToStandardOutput) {
  deformcd::test::TempDir dir;
  const SplitRun r =
      run_split(dir, "bench scenes/phase2.json --backend cpu --methods bvh --frames 2 --plot -");
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_GE(r.out.size(), 8u) << r.err;
  EXPECT_EQ(r.out.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));  // the PNG signature
  EXPECT_NE(r.err.find("bvh"), std::string::npos) << r.err;            // the table went to stderr
  EXPECT_FALSE(fs::exists(fs::path(DEFORMCD_SOURCE_DIR) / "-"));
}

TEST(HardeningCli, DevStdoutReachesAPipeAsAnyUser) {
  // The whole pipeline runs as nobody, as a user's shell would run it (a pipe is reopened
  // through /proc/self/fd with its creator's permissions).
  const CliRun r = run_shell(as_nobody() + " sh -c 'cd " + std::string(DEFORMCD_SOURCE_DIR) +
                             " && " + DEFORMCD_CLI + " " + kCollide + " --json /dev/stdout | cat'");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::size_t json = r.output.find("{\"contacts\"");
  ASSERT_NE(json, std::string::npos) << r.output;
  const std::string line = r.output.substr(json, r.output.find('\n', json) - json);
  EXPECT_GT(nlohmann::json::parse(line).at("contacts").size(), 10u) << r.output;
}

TEST(HardeningCli, DevNullIsWrittenAsAnyUserAndStaysADevice) {
  deformcd::test::TempDir dir;
  fs::permissions(dir.path(), fs::perms::all);
  const SplitRun r = run_split(dir, kCollide + " --json /dev/null", as_nobody());
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

TEST(HardeningCli, OptionsThatCannotTakeStandardOutputSaySo) {
  const CliRun r = run_cli("tetra " + kData + "cube.off --out -");
#ifdef DEFORMCD_HAS_TETGEN
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("tetra writes three files"), std::string::npos) << r.output;
#endif
}

TEST(HardeningCli, ThreadCountsPastTheLimitAreUsageErrorsWithTheLibrarysMessage) {
  for (const char* threads : {"10000000", "257", "-1"}) {
    for (const std::string& command :
         {kCollide, std::string("run scenes/phase1.json --backend cpu --frames 1")}) {
      const CliRun r = run_cli(command + " --threads " + threads);
      EXPECT_EQ(r.status, 2) << r.output;
      EXPECT_NE(r.output.find("--threads: must be 0 (every core) or 1 to 256 "
                              "(deformcd::kMaxThreads), got " +
                              std::string(threads)),
                std::string::npos)
          << r.output;
      EXPECT_LT(r.output.size(), 300u) << r.output;  // not CLI11's 300-digit range
    }
  }
}

TEST(HardeningCli, InfoRefusesCoordinatesPastTheRangeInsteadOfPrintingInfiniteBounds) {
  deformcd::test::TempDir dir;
  std::ofstream(dir / "big.node") << "4 3 0 0\n0 0 0 0\n1 1e39 0 0\n2 0 1e39 0\n3 0 0 1e39\n";
  std::ofstream(dir / "big.ele") << "1 4 0\n0 0 1 2 3\n";
  const CliRun r = run_cli("info " + (dir / "big").string());
  EXPECT_EQ(r.status, 1) << r.output;  // before: 0, with bounds [inf, inf, inf]
  EXPECT_NE(r.output.find("node 1 has coordinate 1e+39, outside +-1e+09 "
                          "(deformcd::kMaxCoordinate)"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("inf"), std::string::npos) << r.output;
}

TEST(HardeningCli, OneExitStatusRuleInEveryCommand) {
  // A missing argument is a usage error (2); a missing input file a failed work (1), named.
  CliRun r = run_cli("info");
  EXPECT_EQ(r.status, 2) << r.output;  // before: 1
  EXPECT_NE(r.output.find("deformcd info: error: give a MODEL, or --gpu"), std::string::npos)
      << r.output;
  r = run_cli("collide " + kData + "cube.off " + kData + "no_such.off --backend cpu");
  EXPECT_EQ(r.status, 1) << r.output;  // before: 2, through CLI11's check
  EXPECT_NE(r.output.find("no_such.off: cannot open"), std::string::npos) << r.output;
  r = run_cli("info " + kData + "no_such.off");
  EXPECT_EQ(r.status, 1) << r.output;
}

TEST(HardeningCli, ARunOfBillionsOfSubstepsIsRefusedUnlessAskedFor) {
  // phase1 runs 16 substeps a frame: 2e9 frames would run for ever, silently.
  const CliRun r = run_cli("run scenes/phase1.json --backend cpu --frames 2000000000");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("the run is 2000000000 frames x 16 substeps = 32000000000 substeps, "
                          "more than 1000000"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("DEFORMCD_LONG_RUN=1"), std::string::npos) << r.output;
}

#if !defined(DEFORMCD_UNDER_ASAN) && defined(DEFORMCD_HAS_GL)
// The case: under `ulimit -v 250000` Mesa's llvmpipe dies of SIGSEGV while it sets up a
// context. The auto backend probes in a child, so the run goes on, on the CPU, with a notice.
// (AddressSanitizer reserves terabytes of address space: no ulimit -v there.)
TEST(HardeningCli, TheAutoProbeCrashingUnderAMemoryLimitFallsBackOnTheCpu) {
  const CliRun cpu =
      run_shell("cd " + std::string(DEFORMCD_SOURCE_DIR) + " && ulimit -v 250000 && " +
                DEFORMCD_CLI + " run scenes/phase1.json --frames 5 --backend cpu");
  ASSERT_EQ(cpu.status, 0) << "the CPU backend itself does not fit the limit: " << cpu.output;
  const CliRun r = run_shell("cd " + std::string(DEFORMCD_SOURCE_DIR) + " && ulimit -v 250000 && " +
                             DEFORMCD_CLI + " run scenes/phase1.json --frames 5");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("using the CPU backend"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("backend    cpu"), std::string::npos) << r.output;
}
#endif

}  // namespace
