#pragma once
// Strict reading of JSON objects: each field is taken by name with its expected type, and
// whatever was not taken is reported as an unknown key. Errors name the file and the JSON
// pointer of the offending value (e.g. "/bodies/1/material/stiffness").

#include <initializer_list>
#include <optional>
#include <set>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace deformcd::scene_detail {

class JsonFields {
 public:
  /// `value` must be an object; `pointer` is its location ("" for the root).
  JsonFields(const nlohmann::json& value, std::string file, std::string pointer);

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
  void reject_unknown(std::initializer_list<const char*> valid) const;

  [[nodiscard]] std::string pointer_of(const std::string& key) const {
    return pointer_ + "/" + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

 private:
  const nlohmann::json& value_;
  std::string file_;
  std::string pointer_;
  std::set<std::string> used_;
};

}  // namespace deformcd::scene_detail
