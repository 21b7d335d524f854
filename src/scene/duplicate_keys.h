#pragma once
// JSON allows a key twice in one object and nlohmann keeps the last one silently: a scene with
// "dt" twice would run with whichever came last. The scene reader refuses it instead.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace deformcd::scene_detail {

/// A parser callback (nlohmann::json::parse(text, std::ref(check))) that throws InputError
/// "FILE: key 'K' appears twice in POINTER" for the first key repeated within one object.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}

  bool operator()(int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed);

 private:
  // One open object or array: the keys seen so far, or the index of the next element.
  struct Level {
    bool is_array = false;
    std::vector<std::string> keys;
    std::size_t index = 0;
  };
  [[nodiscard]] std::string pointer() const;  // of the innermost open object
  void element_done();

  std::string file_;
  std::vector<Level> levels_;
};

}  // namespace deformcd::scene_detail
