#include "scene/duplicate_keys.h"

#include <algorithm>

#include "deformcd/error.h"

namespace deformcd::scene_detail {

bool DuplicateKeyCheck::operator()(int /*depth*/, nlohmann::json::parse_event_t event,
                                   nlohmann::json& parsed) {
  using Event = nlohmann::json::parse_event_t;
  switch (event) {
    case Event::object_start:
      levels_.push_back({});
      break;
    case Event::array_start:
      levels_.push_back({true, {}, 0});
      break;
    case Event::key: {
      const std::string key = parsed.get<std::string>();
      std::vector<std::string>& keys = levels_.back().keys;
      if (std::find(keys.begin(), keys.end(), key) != keys.end()) {
        const std::string where = pointer();
        throw InputError(file_, "key '" + key + "' appears twice in " +
                                    (where.empty() ? std::string("the top-level object") : where) +
                                    " (JSON would keep only the last; give it once)");
      }
      keys.push_back(key);
      break;
    }
    case Event::object_end:
    case Event::array_end:
      levels_.pop_back();
      element_done();
      break;
    case Event::value:
      element_done();
      break;
  }
  return true;
}

void DuplicateKeyCheck::element_done() {
  if (!levels_.empty() && levels_.back().is_array) ++levels_.back().index;
}

std::string DuplicateKeyCheck::pointer() const {
  std::string out;
  // Every open level but the innermost contributes the child being read: its last key or the
  // index of the element being read.
  for (std::size_t i = 0; i + 1 < levels_.size(); ++i) {
    const Level& level = levels_[i];
    out += "/" + (level.is_array ? std::to_string(level.index) : level.keys.back());
  }
  return out;
}

}  // namespace deformcd::scene_detail
