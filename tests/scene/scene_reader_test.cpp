#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "support/mesh_fixtures.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

class SceneReaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "models");
    write_tetgen(test::unit_cube(), dir_ / "models" / "cube");
  }

  fs::path write(const std::string& text) const {
    const fs::path file = dir_ / "scene.json";
    std::ofstream(file) << text;
    return file;
  }
  std::string error_of(const std::string& text) const {
    try {
      (void)read_scene(write(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

TEST_F(SceneReaderTest, ReadsEveryKey) {
  const Scene s = read_scene(write(R"({
    "settings": {"dt": 0.01, "substeps": 4, "gravity": [0, 0, -9.8], "velocity_damping": 0.5,
                 "frames": 120},
    "collision": {"broadphase": "brute", "self": true},
    "bodies": [{"name": "a", "model": "models/cube", "position": [1, 2, 3],
                "rotation": [0, 90, 0], "scale": 2, "velocity": [0, 1, 0], "squash": [1, 0.5, 1],
                "material": {"mass": 3, "stiffness": 1e4, "damping": 0.001},
                "fixed": {"nodes": [0, 1], "box": {"min": [0, 0, 0], "max": [1, 1, 0.1]}},
                "path": {"to": [4, 5, 6]}}]
  })"));
  EXPECT_DOUBLE_EQ(s.settings.dt, 0.01);
  EXPECT_EQ(s.settings.substeps, 4);
  EXPECT_EQ(s.settings.gravity, glm::dvec3(0, 0, -9.8));
  EXPECT_EQ(s.settings.frames, 120);
  EXPECT_EQ(s.collision.broadphase, "brute");
  EXPECT_EQ(s.collision.self, true);
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodySpec& b = s.bodies[0];
  EXPECT_EQ(b.name, "a");
  EXPECT_EQ(b.model, (dir_ / "models" / "cube").lexically_normal());
  EXPECT_EQ(b.position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(b.scale, glm::dvec3(2.0));
  EXPECT_EQ(b.squash, glm::dvec3(1, 0.5, 1));
  EXPECT_EQ(*b.material.mass, 3.0);
  EXPECT_FALSE(b.material.density.has_value());
  EXPECT_EQ(b.fixed.nodes, (std::vector<std::uint32_t>{0, 1}));
  ASSERT_TRUE(b.fixed.box.has_value());
  EXPECT_EQ(*b.path_to, glm::dvec3(4, 5, 6));
}

// material.node_mass_floor: read into the spec (unset when absent: the response decides,
// node_mass_floor_on), refused with its path outside [0, 1].
TEST_F(SceneReaderTest, NodeMassFloorIsReadAndRefusedOutsideZeroToOne) {
  const Scene s = read_scene(write(R"({"bodies": [{"model": "models/cube"},
      {"model": "models/cube", "material": {"node_mass_floor": 0.5}}]})"));
  EXPECT_FALSE(s.bodies[0].material.node_mass_floor.has_value());
  EXPECT_EQ(s.bodies[1].material.node_mass_floor, 0.5);
  for (const char* value : {"1.5", "-0.1"}) {
    const std::string msg = error_of(std::string(R"({"bodies": [{"model": "models/cube",
        "material": {"node_mass_floor": )") +
                                     value + "}}]}");
    EXPECT_NE(msg.find("/bodies/0/material/node_mass_floor"), std::string::npos) << msg;
  }
}

TEST_F(SceneReaderTest, UnknownKeyIsNamedWithItsPathAndTheValidOnes) {
  const std::string msg = error_of(R"({"bodies": [{"model": "models/cube",
      "material": {"stifness": 10}}]})");
  EXPECT_NE(msg.find("scene.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("/bodies/0/material/stifness"), std::string::npos) << msg;
  EXPECT_NE(msg.find("valid keys here: density, mass, stiffness, damping, volume_stiffness, "
                     "node_mass_floor"),
            std::string::npos)
      << msg;
}

TEST_F(SceneReaderTest, WrongTypesAreNamed) {
  std::string msg =
      error_of(R"({"settings": {"dt": "fast"}, "bodies": [{"model": "models/cube"}]})");
  EXPECT_NE(msg.find("/settings/dt: expected a number, found string"), std::string::npos) << msg;
  msg = error_of(R"({"bodies": [{"model": "models/cube", "position": [1, 2]}]})");
  EXPECT_NE(msg.find("/bodies/0/position: expected an array of 3 numbers"), std::string::npos)
      << msg;
  msg = error_of(R"({"settings": {"substeps": 2.5}, "bodies": [{"model": "models/cube"}]})");
  EXPECT_NE(msg.find("/settings/substeps: expected an integer"), std::string::npos) << msg;
}

TEST_F(SceneReaderTest, NumbersNoDoubleHoldsAndHugeNodeIndicesAreNamed) {
  // Found by fuzz_scene: nlohmann::json throws out_of_range for 1e400, which escaped read_scene.
  std::string msg = error_of(R"({"settings": {"gravity": [0, -1e400, 0]},
      "bodies": [{"model": "models/cube"}]})");
  EXPECT_NE(msg.find("invalid JSON"), std::string::npos) << msg;
  EXPECT_NE(msg.find("scene.json"), std::string::npos) << msg;
  // A fixed node index past 32 bits was silently wrapped.
  msg = error_of(R"({"bodies": [{"model": "models/cube", "fixed": {"nodes": [4294967296]}}]})");
  EXPECT_NE(msg.find("/bodies/0/fixed/nodes: node index 4294967296 is out of range"),
            std::string::npos)
      << msg;
}

TEST_F(SceneReaderTest, UnknownBroadPhaseListsTheValidOnes) {
  const std::string msg = error_of(R"({"collision": {"broadphase": "kdtree"},
      "bodies": [{"model": "models/cube"}]})");
  EXPECT_NE(msg.find("/collision/broadphase: unknown broad phase 'kdtree' (valid: none, brute, "
                     "octree, octree-compact, bvh)"),
            std::string::npos)
      << msg;
}

TEST_F(SceneReaderTest, MissingFineModelSaysHowToGenerateIt) {
  const std::string msg = error_of(R"({"bodies": [{"model": "models/fine/lion_100k"}]})");
  EXPECT_NE(msg.find("/bodies/0/model: no such model"), std::string::npos) << msg;
  EXPECT_NE(msg.find("run scripts/make_models.sh --fine"), std::string::npos) << msg;
  EXPECT_EQ(error_of(R"({"bodies": [{"model": "models/sphere"}]})").find("make_models"),
            std::string::npos);
}

TEST_F(SceneReaderTest, MissingModelFileIsNamed) {
  const std::string msg = error_of(R"({"bodies": [{"model": "models/sphere"}]})");
  EXPECT_NE(msg.find("/bodies/0/model: no such model"), std::string::npos) << msg;
  EXPECT_NE(msg.find("sphere"), std::string::npos) << msg;
}

TEST_F(SceneReaderTest, MissingModelIsNamedAsWrittenInTheScene) {
  // Resolved against the scene's folder, the path would read as neither what the scene says
  // nor a path from the working directory.
  const std::string msg = error_of(R"({"bodies": [{"model": "../elsewhere/bunny"}]})");
  EXPECT_NE(msg.find((dir_ / "scene.json").string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("/bodies/0/model: no such model: '../elsewhere/bunny'"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("relative to the scene's folder"), std::string::npos) << msg;
}

TEST_F(SceneReaderTest, BroadPhaseDefaultsToBvh) {
  const Scene s = read_scene(write(R"({"bodies": [{"model": "models/cube"}]})"));
  EXPECT_EQ(s.collision.broadphase, "bvh");
}

TEST_F(SceneReaderTest, SurfaceModelsAreMeshedWithQualityAndTheSurfaceKeptUnlessTheSceneSays) {
  write_off(test::octahedron(), dir_ / "models" / "octahedron.off");
  Scene s = read_scene(write(R"({"bodies": [{"model": "models/octahedron.off"}]})"));
  EXPECT_EQ(s.bodies[0].meshing.quality, 2.0);
  EXPECT_FALSE(s.bodies[0].meshing.max_volume.has_value());
  EXPECT_TRUE(s.bodies[0].meshing.preserve_surface);
  EXPECT_EQ(s.bodies[0].model_as_written, "models/octahedron.off");

  s = read_scene(write(R"({"bodies": [{"model": "models/octahedron.off",
      "meshing": {"quality": 1.4, "max_volume": 0.01, "preserve_surface": false}}]})"));
  EXPECT_EQ(s.bodies[0].meshing.quality, 1.4);
  EXPECT_EQ(s.bodies[0].meshing.max_volume, 0.01);
  EXPECT_FALSE(s.bodies[0].meshing.preserve_surface);
}

TEST_F(SceneReaderTest, BadMeshingIsNamed) {
  write_off(test::octahedron(), dir_ / "models" / "octahedron.off");
  std::string msg = error_of(R"({"bodies": [{"model": "models/octahedron.off",
      "meshing": {"quality": 0.5}}]})");
  EXPECT_NE(msg.find("/bodies/0/meshing/quality: must be at least 1"), std::string::npos) << msg;
  msg = error_of(R"({"bodies": [{"model": "models/octahedron.off",
      "meshing": {"max_volume": 0}}]})");
  EXPECT_NE(msg.find("/bodies/0/meshing/max_volume: must be positive"), std::string::npos) << msg;
  msg = error_of(R"({"bodies": [{"model": "models/octahedron.off",
      "meshing": {"quallity": 2}}]})");
  EXPECT_NE(msg.find("valid keys here: quality, max_volume, preserve_surface"), std::string::npos)
      << msg;
  // A TetGen mesh is already meshed.
  msg = error_of(R"({"bodies": [{"model": "models/cube", "meshing": {"quality": 2}}]})");
  EXPECT_NE(msg.find("/bodies/0/meshing: 'models/cube' is a TetGen mesh"), std::string::npos)
      << msg;
}

TEST_F(SceneReaderTest, InvalidValuesAreRejected) {
  EXPECT_NE(error_of(R"({"settings": {"dt": -1}, "bodies": [{"model": "models/cube"}]})")
                .find("must be positive"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"bodies": [{"model": "models/cube",
                "material": {"density": 1, "mass": 2}}]})")
                .find("either density or mass"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"bodies": []})").find("non-empty array of bodies"), std::string::npos);
  EXPECT_NE(error_of(R"({"bodies": [{"model": "models/cube", "path": {}}]})").find("'to'"),
            std::string::npos);
}

TEST_F(SceneReaderTest, JsonSyntaxErrorGivesTheLine) {
  const std::string msg =
      error_of("{\n  \"bodies\": [\n    {\"model\": \"models/cube\",}\n  ]\n}\n");
  EXPECT_NE(msg.find("scene.json:3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("invalid JSON"), std::string::npos) << msg;
}

TEST(ShippedScenes, AllReadAndTheirModelsExist) {
  for (const char* name : {"hanging", "phase1", "phase2", "crossing16", "fold", "impact", "overlap",
                           "half_overlap", "fold_response", "stack", "slab_drop", "pile"}) {
    const fs::path file = fs::path(DEFORMCD_SOURCE_DIR) / "scenes" / (std::string(name) + ".json");
    const Scene s = read_scene(file);
    EXPECT_FALSE(s.bodies.empty()) << name;
  }
}

}  // namespace
}  // namespace deformcd

namespace deformcd {
namespace {

const char* const kResponseScene = R"({
  "response": RESPONSE,
  "bodies": [{"model": "models/cube"}]
})";

std::string with_response(const std::string& response) {
  std::string text = kResponseScene;
  text.replace(text.find("RESPONSE"), 8, response);
  return text;
}

TEST_F(SceneReaderTest, ResponseIsOffWithoutItAndEveryDefaultWithAnEmptyObject) {
  EXPECT_FALSE(read_scene(write(R"({"bodies": [{"model": "models/cube"}]})")).response);
  const Scene s = read_scene(write(with_response("{}")));
  ASSERT_TRUE(s.response.has_value());
  const ResponseSettings defaults;
  EXPECT_FALSE(s.response->thickness.has_value());
  EXPECT_EQ(s.response->relative_thickness, defaults.relative_thickness);
  EXPECT_EQ(s.response->friction_static, defaults.friction_static);
  EXPECT_EQ(s.response->restitution, defaults.restitution);
}

// Self-collision follows the response unless the scene says: a soft body without it folds
// through itself where another presses it.
TEST_F(SceneReaderTest, SelfCollisionIsOnWithAResponseUnlessTheSceneSays) {
  const Scene bare = read_scene(write(R"({"bodies": [{"model": "models/cube"}]})"));
  EXPECT_FALSE(bare.collision.self.has_value());
  EXPECT_FALSE(self_collision(bare));
  const Scene with = read_scene(write(with_response("{}")));
  EXPECT_FALSE(with.collision.self.has_value());
  EXPECT_TRUE(self_collision(with));
  EXPECT_EQ(with.response->volume_floor, 0.3f);
  EXPECT_EQ(with.response->substep_motion, 0.3f);
  const Scene off = read_scene(write(R"({"collision": {"self": false}, "response": {},
                                         "bodies": [{"model": "models/cube"}]})"));
  EXPECT_EQ(off.collision.self, false);
  EXPECT_FALSE(self_collision(off));
  const Scene on =
      read_scene(write(R"({"collision": {"self": true}, "bodies": [{"model": "models/cube"}]})"));
  EXPECT_TRUE(self_collision(on));
}

TEST_F(SceneReaderTest, ResponseReadsEveryKey) {
  const Scene s = read_scene(write(with_response(
      R"({"thickness": 0.01, "relative_thickness": 0.3, "friction_static": 0.7,
          "friction_dynamic": 0.5, "restitution": 0.25, "untangle_step": 0.05,
          "volume_floor": 0.3, "substep_motion": 0.5, "iterations": 3,
          "sleep": {"speed": 0.2, "time": 1.5}})")));
  ASSERT_TRUE(s.response.has_value());
  EXPECT_FLOAT_EQ(*s.response->thickness, 0.01f);
  EXPECT_FLOAT_EQ(s.response->relative_thickness, 0.3f);
  EXPECT_FLOAT_EQ(s.response->friction_static, 0.7f);
  EXPECT_FLOAT_EQ(s.response->friction_dynamic, 0.5f);
  EXPECT_FLOAT_EQ(s.response->restitution, 0.25f);
  EXPECT_FLOAT_EQ(s.response->untangle_step, 0.05f);
  EXPECT_FLOAT_EQ(s.response->volume_floor, 0.3f);
  EXPECT_FLOAT_EQ(s.response->substep_motion, 0.5f);
  EXPECT_EQ(s.response->iterations, 3);
  ASSERT_TRUE(s.response->sleep.has_value());
  EXPECT_FLOAT_EQ(s.response->sleep->speed, 0.2f);
  EXPECT_FLOAT_EQ(s.response->sleep->time, 1.5f);
}

// Sleeping is off unless asked for; `"sleep": {}` takes every default.
TEST_F(SceneReaderTest, SleepIsOffByDefaultAndAnEmptyObjectTakesTheDefaults) {
  EXPECT_FALSE(read_scene(write(with_response("{}"))).response->sleep.has_value());
  const Scene s = read_scene(write(with_response(R"({"sleep": {}})")));
  ASSERT_TRUE(s.response->sleep.has_value());
  EXPECT_EQ(s.response->sleep->speed, SleepSettings{}.speed);
  EXPECT_EQ(s.response->sleep->time, SleepSettings{}.time);
}

// Each bad value is named by its JSON pointer.
TEST_F(SceneReaderTest, BadResponseValuesNameTheirKey) {
  const struct {
    const char* response;
    const char* pointer;
    const char* says;
  } cases[] = {
      {R"({"thickness": -0.01})", "/response/thickness", "positive"},
      {R"({"thickness": 0})", "/response/thickness", "positive"},
      {R"({"friction_static": -1})", "/response/friction_static", "negative"},
      {R"({"friction_dynamic": -0.1})", "/response/friction_dynamic", "negative"},
      {R"({"friction_static": 0.2, "friction_dynamic": 0.5})", "/response/friction_dynamic",
       "friction_static"},
      {R"({"restitution": 1.5})", "/response/restitution", "between 0 and 1"},
      {R"({"untangle_step": 0})", "/response/untangle_step", "positive"},
      {R"({"volume_floor": 1})", "/response/volume_floor", "below 1"},
      {R"({"volume_floor": -0.1})", "/response/volume_floor", ""},
      {R"({"substep_motion": -1})", "/response/substep_motion", ""},
      {R"({"iterations": 0})", "/response/iterations", "between 1 and 64"},
      {R"({"iterations": 65})", "/response/iterations", "between 1 and 64"},
      {R"({"iterations": 2.5})", "/response/iterations", ""},
      // Gone with the Jacobi iterations it relaxed (the sweeps need none).
      {R"({"volume_relaxation": 1.5})", "/response/volume_relaxation", "unknown"},
      {R"({"thickness": "thin"})", "/response/thickness", ""},
      {R"({"stiffness": 1})", "/response/stiffness", "unknown"},
      {R"({"sleep": {"speed": 0}})", "/response/sleep/speed", "positive"},
      {R"({"sleep": {"time": -1}})", "/response/sleep/time", "positive"},
      {R"({"sleep": {"after": 1}})", "/response/sleep/after", "unknown"},
      {R"({"sleep": true})", "/response/sleep", ""},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(with_response(c.response));
    EXPECT_NE(message.find(c.pointer), std::string::npos) << c.response << ": " << message;
    EXPECT_NE(message.find(c.says), std::string::npos) << c.response << ": " << message;
  }
}

}  // namespace
}  // namespace deformcd
