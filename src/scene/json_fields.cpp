#include "scene/json_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "deformcd/error.h"
#include "scene/scene_keys.h"

namespace deformcd::scene_detail {

JsonFields::JsonFields(const nlohmann::json& value, std::string file, std::string pointer,
                       std::string keys_path)
    : value_(value),
      file_(std::move(file)),
      pointer_(std::move(pointer)),
      keys_path_(std::move(keys_path)),
      valid_(keys_at(keys_path_)) {
  if (!value_.is_object()) {
    throw InputError(file_, (pointer_.empty() ? std::string("/") : pointer_) +
                                ": expected an object, found " + value_.type_name());
  }
}

bool JsonFields::has(const std::string& key) const {
  check_listed(key);
  return value_.contains(key);
}

void JsonFields::fail(const std::string& key, const std::string& message) const {
  throw InputError(file_, pointer_of(key) + ": " + message);
}

void JsonFields::check_listed(const std::string& key) const {
  if (std::find(valid_.begin(), valid_.end(), key) == valid_.end()) {
    throw std::logic_error("scene reader: the key '" + key + "' of '" + keys_path_ +
                           "' is read but not listed in scene_keys.cpp");
  }
}

const nlohmann::json* JsonFields::raw(const std::string& key) {
  check_listed(key);
  auto it = value_.find(key);
  if (it == value_.end()) return nullptr;
  used_.insert(key);
  return &*it;
}

std::optional<double> JsonFields::number(const std::string& key) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  if (!v->is_number()) fail(key, std::string("expected a number, found ") + v->type_name());
  const double d = v->get<double>();
  if (!std::isfinite(d)) fail(key, "expected a finite number");
  return d;
}

std::optional<int> JsonFields::integer(const std::string& key) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  if (!v->is_number_integer())
    fail(key, std::string("expected an integer, found ") + v->type_name());
  const auto i = v->get<long long>();
  if (i < -2147483647LL || i > 2147483647LL) fail(key, "integer out of range");
  return static_cast<int>(i);
}

std::optional<bool> JsonFields::boolean(const std::string& key) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  if (!v->is_boolean()) fail(key, std::string("expected true or false, found ") + v->type_name());
  return v->get<bool>();
}

std::optional<std::string> JsonFields::string(const std::string& key) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  if (!v->is_string()) fail(key, std::string("expected a string, found ") + v->type_name());
  return v->get<std::string>();
}

namespace {

// Positions, velocities, gravity...: the simulation holds them in 32-bit float.
bool fits_float(double v) {
  return std::abs(v) <= static_cast<double>(std::numeric_limits<float>::max());
}

constexpr const char* kPastFloat =
    "a value is past 3.4e+38, the largest 32-bit float (the simulation's type)";

}  // namespace

std::optional<glm::dvec3> JsonFields::vec3(const std::string& key, bool scalar_ok) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  if (scalar_ok && v->is_number()) {
    const double s = v->get<double>();
    if (!std::isfinite(s)) fail(key, "expected a finite number");
    if (!fits_float(s)) fail(key, kPastFloat);
    return glm::dvec3(s);
  }
  const char* expected =
      scalar_ok ? "a number or an array of 3 numbers [x, y, z]" : "an array of 3 numbers [x, y, z]";
  if (!v->is_array() || v->size() != 3) fail(key, std::string("expected ") + expected);
  glm::dvec3 out;
  for (int k = 0; k < 3; ++k) {
    const auto& c = (*v)[static_cast<std::size_t>(k)];
    if (!c.is_number() || !std::isfinite(c.get<double>())) {
      fail(key, std::string("expected ") + expected);
    }
    out[k] = c.get<double>();
    if (!fits_float(out[k])) fail(key, kPastFloat);
  }
  return out;
}

std::optional<JsonFields> JsonFields::object(const std::string& key) {
  const nlohmann::json* v = raw(key);
  if (!v) return std::nullopt;
  return JsonFields(*v, file_, pointer_of(key), keys_path_.empty() ? key : keys_path_ + "." + key);
}

void JsonFields::reject_unknown() const {
  for (const auto& [key, value] : value_.items()) {
    if (used_.count(key)) continue;
    std::ostringstream list;
    const char* sep = "";
    for (const std::string& name : valid_) {
      list << sep << name;
      sep = ", ";
    }
    fail(key, "unknown key '" + key + "' (valid keys here: " + list.str() + ")");
  }
}

}  // namespace deformcd::scene_detail
