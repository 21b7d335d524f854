// `deformcd bench`'s intersection census (apps/deformcd/bench_intersections.h) as a user sees
// it: per-frame counts in the JSON and a summary line, for scenes with a contact response only.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace {

using deformcd::test::CliRun;
using deformcd::test::run_cli;

std::string scene_file(const char* name) {
  return (fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(name) + ".json")).string();
}

// `deformcd bench SCENE --backend cpu --methods bvh` with its JSON report written to `json`.
CliRun bench(const std::string& scene, int threads, int frames, const fs::path& json) {
  return run_cli("bench " + scene + " --backend cpu --methods bvh --threads " +
                 std::to_string(threads) + " --frames " + std::to_string(frames) + " --json " +
                 json.string());
}

nlohmann::json bvh_per_frame(const fs::path& json) {
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  return j.at("scenes").at(0).at("methods").at("bvh").at("per_frame");
}

// overlap starts with the bodies in each other: its first two frames have pairs between the
// bodies and vertices of each inside the other, which the census must count (half_overlap,
// deeper, did the same at six times the cost: 45 s under the sanitizers).
TEST(BenchIntersectionsCli, ResponseSceneReportsTheCensusEveryFrame) {
  deformcd::test::TempDir dir;
  const fs::path json = dir.path() / "bench.json";
  const CliRun r = bench(scene_file("overlap"), 1, 2, json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("intersections (bodies with themselves included): 2 of 2 frames"),
            std::string::npos)
      << r.output;
  const nlohmann::json per_frame = bvh_per_frame(json);
  for (const char* key : {"intersecting_pairs_between", "intersecting_pairs_self",
                          "inside_vertices", "inverted_tetrahedra", "asleep"}) {
    ASSERT_EQ(per_frame.at(key).size(), 2u) << key;
  }
  EXPECT_EQ(per_frame["asleep"][1].get<std::uint64_t>(), 0u) << "bodies asleep while apart";
  for (int f = 0; f < 2; ++f) {
    EXPECT_GT(per_frame["intersecting_pairs_between"][f].get<std::uint64_t>(), 0u);
    EXPECT_GT(per_frame["inside_vertices"][f].get<std::uint64_t>(), 0u);
  }
}

// The stack with the response's three defaults against folding off (self-contact, the volume
// floor, motion-bounded substeps): its soft bodies are crushed where they land (frames 5-10) and
// tetrahedra turn inside out, none before. The census counts them, as a user must see them:
// there the surfaces fold through themselves, which no contact between surface primitives undoes.
TEST(BenchIntersectionsCli, CrushedBodiesShowTheirInvertedTetrahedra) {
  deformcd::test::TempDir dir;
  nlohmann::json scene;
  {
    std::ifstream in(scene_file("stack"));
    scene = nlohmann::json::parse(in);
  }
  for (nlohmann::json& body : scene.at("bodies")) {
    const fs::path model =
        fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / body.at("model").get<std::string>();
    body["model"] = model.lexically_normal().string();
  }
  scene["collision"]["self"] = false;
  scene["response"]["volume_floor"] = 0;
  scene["response"]["substep_motion"] = 0;
  const fs::path lean = dir.path() / "stack_lean.json";
  std::ofstream(lean) << scene.dump(2);
  const fs::path json = dir.path() / "bench.json";
  const CliRun r = bench(lean.string(), 2, 12, json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find(" tetrahedra inverted"), std::string::npos) << r.output;
  const nlohmann::json inverted = bvh_per_frame(json).at("inverted_tetrahedra");
  ASSERT_EQ(inverted.size(), 12u);
  EXPECT_EQ(inverted[0].get<std::uint64_t>(), 0u);
  EXPECT_GT(inverted[11].get<std::uint64_t>(), 10u);
}

// With the defaults the same frames keep all but a few tetrahedra the right way out (the volume
// floor; measured: at most 2 at once, where more than 10 turn without it) and no surface through
// itself.
TEST(BenchIntersectionsCli, WithTheDefaultsTheStackNeitherInvertsNorFolds) {
  deformcd::test::TempDir dir;
  const fs::path json = dir.path() / "bench.json";
  const CliRun r = bench(scene_file("stack"), 2, 12, json);
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json per_frame = bvh_per_frame(json);
  for (std::size_t f = 0; f < 12; ++f) {
    EXPECT_LE(per_frame.at("inverted_tetrahedra")[f].get<std::uint64_t>(), 5u) << "frame " << f + 1;
    EXPECT_EQ(per_frame.at("intersecting_pairs_self")[f].get<std::uint64_t>(), 0u)
        << "frame " << f + 1;
  }
}

TEST(BenchIntersectionsCli, SceneWithoutResponseHasNoCensus) {
  deformcd::test::TempDir dir;
  const fs::path json = dir.path() / "bench.json";
  const CliRun r = bench(scene_file("phase2"), 1, 2, json);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("intersections (bodies"), std::string::npos) << r.output;
  EXPECT_FALSE(bvh_per_frame(json).contains("inside_vertices"));
}

}  // namespace
