// docs/scenes.md against the scene reader: its table lists exactly the keys read_scene accepts
// (deformcd::scene_keys(), the reader's own list), and its JSON examples are scenes the reader
// accepts.

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "deformcd/error.h"
#include "deformcd/scene.h"
#include "scene/json_fields.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;
const fs::path kSource = DEFORMCD_SOURCE_DIR;
const char* const kPage = "docs/scenes.md";

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct Row {
  int line = 0;
  std::vector<std::string> cells;
};

// The rows of the table under "## Every key" whose first cell is a `key`.
std::vector<Row> key_rows() {
  std::istringstream page(read_text(kSource / kPage));
  std::vector<Row> rows;
  bool in_section = false;
  int number = 0;
  for (std::string line; std::getline(page, line);) {
    ++number;
    if (line.rfind("## ", 0) == 0) in_section = line == "## Every key";
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    Row row{number, {}};
    std::istringstream cells(line.substr(1));
    for (std::string cell; std::getline(cells, cell, '|');) {
      const std::size_t b = cell.find_first_not_of(' ');
      const std::size_t e = cell.find_last_not_of(' ');
      row.cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    rows.push_back(row);
  }
  return rows;
}

std::string key_of(const Row& row) {
  const std::string& cell = row.cells.at(0);
  return cell.size() >= 2 ? cell.substr(1, cell.size() - 2) : cell;
}

TEST(SceneReference, ListsEveryKeyTheReaderAcceptsAndNoOther) {
  const std::vector<Row> rows = key_rows();
  ASSERT_FALSE(rows.empty()) << kPage << " has no key table under \"## Every key\"";
  std::set<std::string> documented;
  for (const Row& row : rows) {
    const std::string key = key_of(row);
    EXPECT_TRUE(documented.insert(key).second)
        << kPage << ":" << row.line << ": `" << key << "` has two rows";
    EXPECT_EQ(row.cells.size(), 5u)
        << kPage << ":" << row.line << ": `" << key
        << "`: a row has five cells (key | type | default | unit | meaning)";
    if (row.cells.size() == 5u) {
      EXPECT_FALSE(row.cells[1].empty())
          << kPage << ":" << row.line << ": `" << key << "` has no type";
      EXPECT_FALSE(row.cells[2].empty()) << kPage << ":" << row.line << ": `" << key
                                         << "` has no default (write `required` or `none`)";
      EXPECT_FALSE(row.cells[4].empty())
          << kPage << ":" << row.line << ": `" << key << "` has no meaning";
    }
  }
  const std::set<std::string> accepted(deformcd::scene_keys().begin(),
                                       deformcd::scene_keys().end());
  for (const std::string& key : accepted) {
    EXPECT_TRUE(documented.count(key))
        << kPage << " has no row for the scene key `" << key
        << "`, which read_scene accepts (src/scene/scene_keys.cpp): add \"| `" << key
        << "` | type | default | unit | meaning |\" to its table";
  }
  for (const std::string& key : documented) {
    EXPECT_TRUE(accepted.count(key))
        << kPage << " documents the scene key `" << key
        << "`, which read_scene does not accept (src/scene/scene_keys.cpp): remove its row";
  }
}

// The JSON blocks of the page, each read as a scene from a folder beside the repository's
// assets/ (the examples name their models as the shipped scenes do, "../assets/models/...").
TEST(SceneReference, ItsJsonExamplesAreScenesTheReaderAccepts) {
  std::istringstream page(read_text(kSource / kPage));
  const deformcd::test::TempDir dir;
  fs::create_directory(dir / "scenes");
  fs::create_directory_symlink(kSource / "assets", dir / "assets");
  int number = 0;
  int examples = 0;
  int start = 0;
  std::string json;
  bool in_json = false;
  for (std::string line; std::getline(page, line);) {
    ++number;
    if (!in_json && line == "```json") {
      in_json = true;
      start = number;
      json.clear();
    } else if (in_json && line == "```") {
      in_json = false;
      ++examples;
      const fs::path file = dir / "scenes" / ("example_" + std::to_string(start) + ".json");
      std::ofstream(file) << json;
      try {
        const deformcd::Scene scene = deformcd::read_scene(file);
        EXPECT_FALSE(scene.bodies.empty());
      } catch (const deformcd::Error& e) {
        ADD_FAILURE() << kPage << ":" << start << ": the JSON example is not a scene the "
                      << "reader accepts: " << e.what();
      }
    } else if (in_json) {
      json += line + "\n";
    }
  }
  EXPECT_GT(examples, 0) << kPage << " has no ```json example";
}

// The reader reads no key its table lacks (JsonFields throws std::logic_error otherwise): every
// shipped scene uses most keys, and reads.
TEST(SceneReference, EveryShippedSceneReads) {
  int scenes = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(kSource / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    EXPECT_NO_THROW((void)deformcd::read_scene(entry.path())) << entry.path();
  }
  EXPECT_GE(scenes, 9);
}

// A reader that asks for a key its table lacks is a bug caught at the first read, not a key
// that the reference would miss.
TEST(SceneReference, TheReaderCannotReadAKeyItsTableLacks) {
  const nlohmann::json settings = {{"dt", 0.01}};
  deformcd::scene_detail::JsonFields f(settings, "x.json", "/settings", "settings");
  EXPECT_EQ(f.number("dt"), 0.01);
  EXPECT_THROW((void)f.number("time_step"), std::logic_error);
  EXPECT_THROW((void)f.has("time_step"), std::logic_error);
}

TEST(SceneReference, KeysAreDottedPathsOfTheObjectsTheyBelongTo) {
  const std::vector<std::string>& keys = deformcd::scene_keys();
  const std::set<std::string> all(keys.begin(), keys.end());
  EXPECT_EQ(all.size(), keys.size()) << "a key listed twice";
  for (const std::string& key : keys) {
    const std::size_t dot = key.rfind('.');
    if (dot == std::string::npos) continue;
    std::string parent = key.substr(0, dot);
    EXPECT_TRUE(all.count(parent) || all.count(parent.substr(0, parent.size() - 2)))
        << key << ": its object " << parent << " is not a key";
  }
  EXPECT_TRUE(all.count("bodies[].material.stiffness"));
  EXPECT_TRUE(all.count("response.sleep.time"));
}

}  // namespace
