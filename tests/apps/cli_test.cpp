// The deformcd tool as a user runs it: exit codes, messages, and no partial output on failure.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

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
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("no-such-flag"), std::string::npos) << r.output;
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
