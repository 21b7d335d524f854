#pragma once
// The shipped scenes (scenes/*.json) by name, sorted: the tests that run every one of them.

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace deformcd::test {

/// The stems of scenes/*.json in the source tree, sorted.
inline std::vector<std::string> shipped_scene_names() {
  std::vector<std::string> names;
  const std::filesystem::path folder = std::filesystem::path(DEFORMCD_SOURCE_DIR) / "scenes";
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace deformcd::test
