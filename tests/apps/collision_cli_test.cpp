// `deformcd run --contacts` and `deformcd bench` as a user runs them: the files they write, and
// their errors.

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace {

using deformcd::test::CliRun;
using deformcd::test::run_cli;

std::string scene(const char* name) {
  return (fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(name) + ".json")).string();
}

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

class CollisionCli : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  deformcd::test::TempDir dir_;
};

TEST_F(CollisionCli, ContactsFileHasOneSortedLinePerFrameAndIsTheSameForEveryBroadPhase) {
  constexpr int kFrames = 12;
  for (const char* method : {"brute", "octree"}) {
    const CliRun r =
        run_cli("run " + scene("phase2") + " --backend cpu --frames " + std::to_string(kFrames) +
                " --broadphase " + method + " --contacts " + path(std::string(method) + ".jsonl"));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("collision  " + std::string(method)), std::string::npos) << r.output;
  }
  const std::vector<std::string> brute = lines_of(path("brute.jsonl"));
  const std::vector<std::string> octree = lines_of(path("octree.jsonl"));
  ASSERT_EQ(brute.size(), kFrames + 1u);  // frames 0..N
  EXPECT_EQ(brute, octree);
  int frames_in_contact = 0;
  for (std::size_t f = 0; f < brute.size(); ++f) {
    const nlohmann::json line = nlohmann::json::parse(brute[f]);
    EXPECT_EQ(line.at("frame").get<std::size_t>(), f);
    const nlohmann::json& contacts = line.at("contacts");
    frames_in_contact += contacts.empty() ? 0 : 1;
    std::tuple<int, int, int, int> previous{-1, -1, -1, -1};
    for (const nlohmann::json& c : contacts) {
      const auto key = std::make_tuple(c["a"]["body"].get<int>(), c["a"]["face"].get<int>(),
                                       c["b"]["body"].get<int>(), c["b"]["face"].get<int>());
      EXPECT_LT(previous, key) << "frame " << f << ": not sorted";
      previous = key;
      EXPECT_LT(std::get<0>(key), std::get<2>(key));
      EXPECT_EQ(c["a"]["nodes"].size(), 3u);
      EXPECT_EQ(c["b"]["nodes"].size(), 3u);
      if (c.contains("coplanar")) {
        EXPECT_TRUE(c["segment"].is_null());
      } else {
        ASSERT_EQ(c["segment"].size(), 2u);
        EXPECT_EQ(c["segment"][0].size(), 3u);
      }
    }
  }
  EXPECT_GE(frames_in_contact, 2);
  EXPECT_TRUE(nlohmann::json::parse(brute.front())["contacts"].empty());
}

TEST_F(CollisionCli, SelfCollisionSceneReportsContactsWithinTheBody) {
  // scenes/fold.json sets "collision": {"self": true}: the plate's faces against each other.
  const CliRun r = run_cli("run " + scene("fold") + " --backend cpu --frames 32 --contacts " +
                           path("fold.jsonl"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<std::string> lines = lines_of(path("fold.jsonl"));
  ASSERT_EQ(lines.size(), 33u);
  std::size_t contacts = 0;
  for (const std::string& text : lines) {
    const nlohmann::json line = nlohmann::json::parse(text);
    for (const nlohmann::json& c : line.at("contacts")) {
      EXPECT_EQ(c["a"]["body"], 0);
      EXPECT_EQ(c["b"]["body"], 0);
      EXPECT_LT(c["a"]["face"].get<int>(), c["b"]["face"].get<int>());
      ++contacts;
    }
  }
  EXPECT_GT(contacts, 0u);  // the flaps crushed into each other, from frame 28
  EXPECT_TRUE(nlohmann::json::parse(lines.front())["contacts"].empty());  // flat at rest
}

TEST_F(CollisionCli, BadContactsPathFailsBeforeRunningAndLeavesNothing) {
  const CliRun r = run_cli("run " + scene("phase2") + " --backend cpu --frames 3 --contacts " +
                           path("missing_dir/out.jsonl"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("missing_dir/out.jsonl"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(dir_.path()));
}

TEST_F(CollisionCli, UnknownBroadPhaseListsTheValidOnes) {
  const CliRun r = run_cli("run " + scene("phase2") + " --backend cpu --frames 3 --broadphase kd");
  EXPECT_EQ(r.status, 2) << r.output;  // a usage error
  EXPECT_NE(
      r.output.find("unknown broad phase 'kd' (valid: none, brute, octree, octree-compact, bvh)"),
      std::string::npos)
      << r.output;
}

TEST_F(CollisionCli, BenchJsonHasEveryKeyAndEqualPairCounts) {
  const CliRun r = run_cli("bench " + scene("phase2") +
                           " --backend cpu --frames 12 --methods brute,octree --json " +
                           path("bench.json") + " --csv " + path("bench.csv"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("V1/V2"), std::string::npos) << r.output;
  std::ifstream in(path("bench.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("scenes").size(), 1u);
  const nlohmann::json& s = j["scenes"][0];
  EXPECT_EQ(s.at("backend"), "cpu");
  EXPECT_TRUE(s.at("methods_agree").get<bool>());
  const nlohmann::json& brute = s.at("methods").at("brute");
  const nlohmann::json& octree = s.at("methods").at("octree");
  for (const nlohmann::json* m : {&brute, &octree}) {
    EXPECT_GT(m->at("total_s").get<double>(), 0.0);
    EXPECT_GT(m->at("collision_s").get<double>(), 0.0);
    EXPECT_GT(m->at("simulation_s").get<double>(), 0.0);
    for (const char* stage : {"before", "contact", "after"}) {
      EXPECT_GT(m->at("ms_per_frame").at(stage).get<double>(), 0.0) << stage;
      EXPECT_GT(m->at("frames_per_stage").at(stage).get<int>(), 0) << stage;
    }
  }
  EXPECT_GT(brute.at("pairs").get<long>(), 0);
  EXPECT_EQ(brute.at("pairs"), octree.at("pairs"));
  const double v1 = brute["total_s"].get<double>();
  const double v2 = octree["total_s"].get<double>();
  EXPECT_NEAR(s.at("improvement").at("octree").get<double>(), (v1 - v2) / v2, 1e-9);
  EXPECT_EQ(lines_of(path("bench.csv")).size(), 3u);  // header + 2 methods

  // How it was measured, and every frame's numbers.
  EXPECT_EQ(j.at("deformcd_version"), DEFORMCD_VERSION);
  EXPECT_EQ(j.at("repeat"), 1);
  EXPECT_GE(j.at("threads").get<int>(), 1);
  EXPECT_GE(j.at("warmup_frames").get<int>(), 0);
  for (const nlohmann::json* m : {&brute, &octree}) {
    const nlohmann::json& per_frame = m->at("per_frame");
    std::uint64_t contacts = 0;
    std::uint64_t candidates = 0;
    for (const char* key : {"simulation_ms", "collision_ms", "contacts", "candidates"})
      ASSERT_EQ(per_frame.at(key).size(), 12u) << key;
    for (int f = 0; f < 12; ++f) {
      EXPECT_GT(per_frame["simulation_ms"][f].get<double>(), 0.0);
      contacts += per_frame["contacts"][f].get<std::uint64_t>();
      candidates += per_frame["candidates"][f].get<std::uint64_t>();
    }
    EXPECT_EQ(contacts, m->at("pairs").get<std::uint64_t>());
    EXPECT_EQ(candidates, m->at("candidates").get<std::uint64_t>());
    EXPECT_GE(candidates, contacts);
  }
  const std::vector<std::string> csv = lines_of(path("bench.csv"));
  EXPECT_EQ(csv[0],
            "scene,backend,device,method,frames,repeat,threads,total_s,simulation_s,collision_s,"
            "ms_before,ms_contact,ms_after,cd_ms_before,cd_ms_contact,cd_ms_after,pairs,"
            "candidates,improvement,deformcd_version,device_times,device_ms_before,"
            "device_ms_contact,device_ms_after,cd_device_ms_before,cd_device_ms_contact,"
            "cd_device_ms_after");
  EXPECT_NE(csv[1].find(",brute,12,1,"), std::string::npos) << csv[1];
  // No device to time on the CPU: no device keys, empty device columns.
  EXPECT_EQ(s.at("device_times"), "none");
  EXPECT_FALSE(brute.contains("device_ms_per_frame"));
  EXPECT_NE(csv[1].find(",none,,,,,,"), std::string::npos) << csv[1];
}

#ifdef DEFORMCD_HAS_GL
TEST_F(CollisionCli, BenchOnGlReportsTheStagesDeviceTimesAndWhatTheyAre) {
  const CliRun r = run_cli("bench " + scene("phase2") + " --backend gl --frames 3 --methods bvh " +
                           "--json " + path("bench.json") + " --csv " + path("bench.csv"));
  if (r.status != 0 && std::getenv("DEFORMCD_REQUIRE_GL") == nullptr) {
    GTEST_SKIP() << "no OpenGL 4.3 context: " << r.output;
  }
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(path("bench.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& s = j.at("scenes").at(0);
  const std::string times = s.at("device_times").get<std::string>();
  EXPECT_TRUE(times == "gpu" || times == "cpu") << times;
  // The device-time table only where timer queries time the work (a GPU); a software renderer
  // is named as such instead, in the JSON and in the printed output (its queries read ~0).
  const bool table = r.output.find("device time (GL timer queries") != std::string::npos;
  EXPECT_EQ(table, times == "gpu") << r.output;
  if (s.at("device").get<std::string>().find("llvmpipe") != std::string::npos) {
    EXPECT_EQ(times, "cpu");
    EXPECT_NE(r.output.find("no device-time table: the renderer is a software one"),
              std::string::npos)
        << r.output;
  }
  const nlohmann::json& bvh = s.at("methods").at("bvh");
  for (const char* key : {"simulation_device_ms", "collision_device_ms"}) {
    ASSERT_EQ(bvh.at("per_frame").at(key).size(), 3u) << key;
    for (const nlohmann::json& v : bvh["per_frame"][key])
      EXPECT_GE(v.get<double>(), 0.0) << key;
  }
  EXPECT_GE(bvh.at("device_collision_s").get<double>(), 0.0);
  for (const char* stage : {"before", "contact", "after"}) {
    EXPECT_TRUE(bvh.at("device_ms_per_frame").contains(stage)) << stage;
    EXPECT_TRUE(bvh.at("collision_device_ms_per_frame").contains(stage)) << stage;
  }
  const std::vector<std::string> csv = lines_of(path("bench.csv"));
  ASSERT_EQ(csv.size(), 2u);
  EXPECT_NE(csv[1].find("," + times + ","), std::string::npos) << csv[1];
  EXPECT_EQ(csv[1].find(",,"), std::string::npos) << csv[1];  // every device column filled
}
#endif

TEST_F(CollisionCli, BenchDrawsAChartNamingItsFile) {
  if (deformcd::test::run_shell("command -v gnuplot").status != 0) {
    GTEST_SKIP() << "gnuplot is not installed (scripts/install_deps.sh installs it)";
  }
  const CliRun r =
      run_cli("bench " + scene("phase2") + " --backend cpu --frames 4 --methods brute,bvh --plot " +
              path("chart.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("plot       " + path("chart.png")), std::string::npos) << r.output;
  std::ifstream png(path("chart.png"), std::ios::binary);
  std::array<char, 8> signature{};
  png.read(signature.data(), signature.size());
  EXPECT_EQ(std::string(signature.data() + 1, 3), "PNG");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_.path()), fs::directory_iterator()), 1)
      << "temporary files left behind";
}

TEST_F(CollisionCli, ASceneOfTheShippedSurfacesRunsThroughContact) {
  // Phase 2 with the bunny and the dragon as surface files: meshed with quality and the surface
  // kept, it runs through the contact (plain TetGen -p blew up at frame 1).
  std::ifstream in(scene("phase2"));
  std::stringstream text;
  text << in.rdbuf();
  std::string json = text.str();
  const std::string models = std::string(DEFORMCD_SOURCE_DIR) + "/assets/models/";
  for (const char* name : {"bunny", "dragon"}) {
    const std::string from = "\"../assets/models/" + std::string(name) + "\"";
    const std::size_t at = json.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    json.replace(at, from.size(), "\"" + models + "surfaces/" + name + ".off\"");
  }
  std::ofstream(path("phase2_surfaces.json")) << json;
  const CliRun r = run_cli("run " + path("phase2_surfaces.json") + " --backend cpu --frames 90");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("tetrahedralizing " + models + "surfaces/bunny.off (TetGen -pq2Y)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("collision  bvh: "), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(" 0 frames in contact"), std::string::npos) << r.output;
}

// On a response scene the bodies meet and rebound without intersecting: the summary says what
// the response did (frames with constraints between the bodies, the most at once, the frames with
// a body's own, the closest the surfaces came against the thickness kept), and no line reads as
// if nothing happened ("0 frames in contact", "0 proximity constraints"). The impact scene's
// bodies first come within their thickness at frame 15 (of 200); 24 frames take it into contact,
// and each body's own pairs (self-contact, on by default) are constraints in every frame.
TEST_F(CollisionCli, RunOnAResponseSceneSaysWhatTheResponseDid) {
  const CliRun r = run_cli("run " + scene("impact") + " --backend cpu --frames 24");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("intersect  bvh: no intersecting faces in frames 0-24 (the response "
                          "kept the surfaces apart)"),
            std::string::npos)
      << r.output;
  const std::string start = "response   constraints between bodies in ";
  const std::size_t response = r.output.find(start);
  ASSERT_NE(response, std::string::npos) << r.output;
  // "in N of 24 frames (F-L), at most M at once (frame K)", 0 < N < 24: apart before frame 15.
  std::istringstream line(r.output.substr(response + start.size()));
  int frames_with_constraints = 0;
  std::string of;
  int frames = 0;
  line >> frames_with_constraints >> of >> frames;
  EXPECT_GT(frames_with_constraints, 0) << r.output;
  EXPECT_LE(frames_with_constraints, 24 - 13) << r.output;
  EXPECT_EQ(frames, 24) << r.output;
  EXPECT_NE(r.output.find("; a body's own (self-contact) in 24 frames"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(" x the thickness kept ("), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("in contact"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(" 0 proximity constraints"), std::string::npos) << r.output;
}

TEST_F(CollisionCli, BenchRejectsNoneAndAutoWithOthers) {  // usage errors
  EXPECT_EQ(run_cli("bench " + scene("phase2") + " --backend cpu --methods brute,none").status, 2);
  EXPECT_EQ(run_cli("bench " + scene("phase2") + " --backend auto,gl").status, 2);
  EXPECT_EQ(run_cli("bench " + scene("phase2") + " --backend metal").status, 2);
}

// Without --backend, bench measures what `run`'s auto rule would choose: GL and the CPU on a
// hardware GL device, else (a software renderer such as llvmpipe, or no GL) the CPU alone,
// saying why. The library's verdict on this machine comes from `info --gpu --json`.
TEST_F(CollisionCli, BenchWithoutBackendFollowsTheAutoRule) {
  std::vector<std::string> expected = {"cpu"};
#ifdef DEFORMCD_HAS_GL
  const CliRun info = run_cli("info --gpu --json");
  if (info.status == 0) {
    const nlohmann::json device = nlohmann::json::parse(info.output.substr(info.output.find('{')));
    const bool software = device.at("software_renderer").get<bool>();
    EXPECT_EQ(device.at("auto_backend").get<std::string>(), software ? "cpu" : "gl");
    if (!software) expected = {"gl", "cpu"};
  }
#endif
  const CliRun r = run_cli("bench " + scene("phase2") + " --frames 2 --methods brute,bvh --json " +
                           path("bench.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(path("bench.json"));
  const nlohmann::json j = nlohmann::json::parse(in);
  std::vector<std::string> measured;
  for (const nlohmann::json& s : j.at("scenes"))
    measured.push_back(s.at("backend").get<std::string>());
  EXPECT_EQ(measured, expected) << r.output;
  if (expected.size() == 1) {
    EXPECT_NE(r.output.find("bench measures the CPU backend only: "), std::string::npos)
        << r.output;
  }
  // A table per backend, each with its own heading and no other backend's caveats.
  const std::size_t cpu_table = r.output.find("phase2.json on cpu (");
  ASSERT_NE(cpu_table, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("glFinish", cpu_table), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Rows measured one after the other", cpu_table), std::string::npos)
      << r.output;
}

}  // namespace

// `deformcd collide`: surface files through the public Detector, no simulation, no TetGen.
TEST_F(CollisionCli, CollideWritesTheContactsOfSurfaceFilesInTheirNumbering) {
  const std::string data = std::string(DEFORMCD_SOURCE_DIR) + "/tests/data/io/";
  std::optional<std::string> reference;
  for (const char* method : {"brute", "octree", "octree-compact", "bvh"}) {
    const std::string out = path(std::string(method) + ".json");
    const CliRun r =
        run_cli("collide " + data + "cube.off " + data + "octahedron.stl --backend cpu" +
                " --broadphase " + method + " --json " + out);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("intersecting triangle pairs"), std::string::npos) << r.output;
    const std::vector<std::string> lines = lines_of(out);
    ASSERT_EQ(lines.size(), 1u);
    const nlohmann::json j = nlohmann::json::parse(lines[0]);
    ASSERT_GT(j.at("contacts").size(), 10u);
    for (const nlohmann::json& c : j.at("contacts")) {
      EXPECT_EQ(c.at("a").at("body"), 0);
      EXPECT_EQ(c.at("b").at("body"), 1);
      EXPECT_LT(c.at("a").at("face").get<int>(), 12);  // the cube.off's 12 triangles
      EXPECT_LT(c.at("b").at("face").get<int>(), 8);   // the octahedron's 8
      EXPECT_TRUE(c.contains("segment"));
    }
    if (!reference) reference = lines[0];
    EXPECT_EQ(lines[0], *reference) << method;
  }
}

TEST_F(CollisionCli, CollideChecksItsOutputFirstAndNamesBadFiles) {
  const std::string data = std::string(DEFORMCD_SOURCE_DIR) + "/tests/data/io/";
  CliRun r = run_cli("collide " + data + "cube.off " + data + "cube.off --json " +
                     path("missing/dir/out.json"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("missing/dir/out.json"), std::string::npos) << r.output;
  r = run_cli("collide " + data + "cube.off " + data + "cube.node");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("cube.node: not a surface file"), std::string::npos) << r.output;
}
