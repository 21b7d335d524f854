// Scenes that name surface models: load_model is a scene's MeshingLoader, and each surface is
// meshed with its body's `meshing` (by default quality with the surface kept).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "deformcd/scene.h"
#include "deformcd/tetrahedralize.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

class SceneSurfaceModels : public ::testing::Test {
 protected:
  Scene scene(const std::string& body) const {
    const fs::path file = dir_.path() / "scene.json";
    std::ofstream(file) << R"({"bodies": [)" << body << "]}";
    return read_scene(file);
  }
  static std::string bunny() {
    return (fs::path(DEFORMCD_SOURCE_DIR) / "assets/models/surfaces/bunny.off").string();
  }
  test::TempDir dir_;
};

TEST_F(SceneSurfaceModels, ByDefaultTheSurfaceIsKeptAndTheInsideHasNodes) {
  // The shipped bunny: 1,112 vertices, 2,220 triangles. Plain TetGen -p put all 1,612 nodes on
  // a re-meshed surface of 3,220 faces, and phase 2 blew up at frame 1.
  const std::vector<BodyInit> bodies =
      make_scene_bodies(scene(R"({"model": ")" + bunny() + R"("})"), load_model, 10);
  ASSERT_EQ(bodies.size(), 1u);
  const Body& body = bodies[0].body;
  EXPECT_EQ(body.faces.size(), 2220u);
  EXPECT_GT(body.positions.size(), 1112u + 100u);  // interior nodes
}

TEST_F(SceneSurfaceModels, TheSceneSetsTheMeshing) {
  const std::size_t coarse =
      make_scene_bodies(scene(R"({"model": ")" + bunny() + R"("})"), load_model, 10)[0]
          .body.tetrahedra.size();
  const std::size_t fine = make_scene_bodies(scene(R"({"model": ")" + bunny() +
                                                   R"(", "meshing": {"max_volume": 2e-5}})"),
                                             load_model, 10)[0]
                               .body.tetrahedra.size();
  EXPECT_GT(fine, 2 * coarse);  // volume 0.2 m^3: at least 10,000 tetrahedra
}

TEST_F(SceneSurfaceModels, TheSceneReferencesExampleLoads) {
  // The example of docs/scenes.md ("## An example"), its ../assets paths made absolute.
  std::ifstream in(fs::path(DEFORMCD_SOURCE_DIR) / "docs/scenes.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::size_t begin = page.find("```json\n", page.find("## An example")) + 8;
  std::string json = page.substr(begin, page.find("```", begin) - begin);
  const std::string assets = std::string(DEFORMCD_SOURCE_DIR) + "/assets";
  for (std::size_t at; (at = json.find("../assets")) != std::string::npos;)
    json.replace(at, 9, assets);
  const fs::path file = dir_.path() / "reference_scene.json";
  std::ofstream(file) << json;
  const Scene scene = read_scene(file);
  ASSERT_EQ(scene.bodies.size(), 2u);
  EXPECT_EQ(scene.bodies[1].meshing.quality, 1.4);
  const std::vector<BodyInit> bodies = make_scene_bodies(scene, load_model, 10);
  EXPECT_EQ(bodies[1].body.faces.size(), 5156u);  // the lion's surface, kept
  EXPECT_GE(bodies[0].fixed.size(), 3u);          // the fixed box holds nodes
}

}  // namespace
}  // namespace deformcd
