#pragma once
// Strict reading of JSON objects: each field is taken by name with its expected type, and
// whatever was not taken is reported as an unknown key. Errors name the file and the JSON
// pointer of the offending value (e.g. "/bodies/1/material/stiffness"). Each object knows its
// place in the scene's key table (scene_keys.h): a getter asked for a key the table does not
// list throws std::logic_error, so the table cannot leave out a key the reader reads.

#include <optional>
#include <set>
#include <span>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace deformcd::scene_detail {

class JsonFields {
 public:
  /// `value` must be an object; `pointer` is its location ("" for the root) and `keys_path`
  /// its entry in the key table ("" for the root, "bodies[]" for an element of `bodies`).
  JsonFields(const nlohmann::json& value, std::string file, std::string pointer,
             std::string keys_path);

  [[nodiscard]] bool has(const std::string& key) const;
  [[nodiscard]] std::optional<double> number(const std::string& key);
  [[nodiscard]] std::optional<int> integer(const std::string& key);
  [[nodiscard]] std::optional<bool> boolean(const std::string& key);
  [[nodiscard]] std::optional<std::string> string(const std::string& key);
  /// [x, y, z] of numbers; with `scalar_ok`, a single number s means [s, s, s].
  [[nodiscard]] std::optional<glm::dvec3> vec3(const std::string& key, bool scalar_ok = false);
  /// A nested object's fields, or nullopt when absent.
  [[nodiscard]] std::optional<JsonFields> object(const std::string& key);
  /// The raw value (marked as used), or nullptr when absent.
  [[nodiscard]] const nlohmann::json* raw(const std::string& key);

  /// Throws for the first key that no getter asked for, listing the valid ones.
  void reject_unknown() const;

  [[nodiscard]] std::string pointer_of(const std::string& key) const {
    return pointer_ + "/" + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  // Throws std::logic_error when the key table has no `key` for this object.
  void check_listed(const std::string& key) const;

  const nlohmann::json& value_;
  std::string file_;
  std::string pointer_;
  std::string keys_path_;
  std::span<const std::string> valid_;
  std::set<std::string> used_;
};

}  // namespace deformcd::scene_detail
