// Issue 34, item 6: scene values checked in the type they are used in, duplicate keys and body
// names refused, a model's error named with the scene key that named it, and control bytes of
// an input file kept off the terminal.

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/scene.h"
#include "support/mesh_fixtures.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace deformcd {
namespace {

class SceneHardening : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "models");
    write_tetgen(test::unit_cube(), dir_ / "models" / "cube");
  }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path file = dir_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  std::string error_of(const std::string& text) const {
    try {
      (void)read_scene(write("scene.json", text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

const char* kCube = R"({"model": "models/cube", "name": "a"})";

TEST_F(SceneHardening, ValuesAreCheckedAsTheFloatsTheyBecome) {
  std::string msg =
      error_of(R"({"settings": {"dt": 1e300}, "bodies": [)" + std::string(kCube) + "]}");
  EXPECT_NE(msg.find("/settings/dt"), std::string::npos) << msg;
  EXPECT_NE(msg.find("32-bit float"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1e+300"), std::string::npos) << msg;
  msg = error_of(R"({"settings": {"dt": 1e-50}, "bodies": [)" + std::string(kCube) + "]}");
  EXPECT_NE(msg.find("/settings/dt"), std::string::npos) << msg;  // 0 as a float
  msg = error_of(R"({"settings": {"gravity": [0, -1e39, 0]}, "bodies": [)" + std::string(kCube) +
                 "]}");
  EXPECT_NE(msg.find("/settings/gravity"), std::string::npos) << msg;
  EXPECT_NE(msg.find("3.4e+38"), std::string::npos) << msg;
  EXPECT_EQ(error_of(R"({"settings": {"dt": 3e38}, "bodies": [)" + std::string(kCube) + "]}"), "");
}

TEST_F(SceneHardening, AKeyGivenTwiceIsRefusedNamingItAndWhere) {
  EXPECT_EQ(error_of(R"({"settings": {"dt": 0.01, "substeps": 2, "dt": 0.02}, "bodies": [)" +
                     std::string(kCube) + "]}"),
            (dir_ / "scene.json").string() +
                ": key 'dt' appears twice in /settings (JSON would keep only the last; give it "
                "once)");
  const std::string msg = error_of(
      R"({"bodies": [{"model": "models/cube", "name": "a"},
                     {"model": "models/cube", "name": "b", "material": {"stiffness": 1, "stiffness": 2}}]})");
  EXPECT_NE(msg.find("key 'stiffness' appears twice in /bodies/1/material"), std::string::npos)
      << msg;
  EXPECT_NE(error_of(R"({"bodies": [], "bodies": [)" + std::string(kCube) + "]}")
                .find("key 'bodies' appears twice in the top-level object"),
            std::string::npos);
  // The same key in different objects is fine.
  EXPECT_EQ(error_of(R"({"bodies": [{"model": "models/cube", "name": "a"},
                                     {"model": "models/cube", "name": "b"}]})"),
            "");
}

TEST_F(SceneHardening, TwoBodiesOfOneNameAreRefused) {
  std::string msg = error_of(R"({"bodies": [{"model": "models/cube", "name": "x"},
                                            {"model": "models/cube", "name": "y"},
                                            {"model": "models/cube", "name": "x"}]})");
  EXPECT_NE(msg.find("/bodies/2: body name 'x' is also body 0's"), std::string::npos) << msg;
  // A name given that is another body's default name (its model's) collides too.
  msg = error_of(
      R"({"bodies": [{"model": "models/cube"}, {"model": "models/cube", "name": "cube"}]})");
  EXPECT_NE(msg.find("/bodies/1: body name 'cube' is also body 0's"), std::string::npos) << msg;
  // Bodies left unnamed may share their model's name: they are told apart by index.
  EXPECT_EQ(error_of(R"({"bodies": [{"model": "models/cube"}, {"model": "models/cube"}]})"), "");
}

TEST_F(SceneHardening, AModelThatCannotBeReadIsNamedWithTheSceneAndTheKey) {
  const Scene scene =
      read_scene(write("scene.json", R"({"bodies": [)" + std::string(kCube) + "]}"));
  try {
    (void)make_scene_bodies(
        scene,
        [](const fs::path& model) -> TetMesh {
          throw InputError(model.string() + ".node", "cannot open: Permission denied");
        },
        10);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir_ / "scene.json").string() + ": /bodies/0/model ('models/cube'): " +
                  (dir_ / "models" / "cube").string() + ".node: cannot open: Permission denied");
  }
}

TEST_F(SceneHardening, ControlBytesOfAnInputFileAreEscapedInMessages) {
  // An OSC sequence that would retitle the terminal, in an OFF header.
  const fs::path off =
      write("evil.off", "OFF\x1b]0;owned\x07 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  try {
    (void)read_surface(off);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\x1b'), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\x07'), std::string::npos) << msg;
    EXPECT_NE(msg.find("\\x1b]0;owned\\x07"), std::string::npos) << msg;
  }
  const InputError c1("f",
                      "a \xc2\x9b"
                      "31m CSI and a tab\t");
  EXPECT_EQ(std::string(c1.what()), "f: a \\x9b31m CSI and a tab\\x09");
  const InputError utf8("f", "caf\xc3\xa9 stays");  // printable UTF-8 is left alone
  EXPECT_EQ(std::string(utf8.what()), "f: caf\xc3\xa9 stays");
}

}  // namespace
}  // namespace deformcd
