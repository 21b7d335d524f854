#pragma once
// Appending numbers to text output without iostreams: shortest round-trip doubles.

#include <charconv>
#include <cstdint>
#include <string>

namespace deformcd::io {

/// Appends `value` in the shortest form that reads back (with strtod or from_chars) to exactly
/// the same double.
inline void append_real(std::string& out, double value) {
  char buffer[32];  // the longest shortest-form double, "-2.2250738585072014e-308", is 24
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

inline void append_integer(std::string& out, std::uint64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

}  // namespace deformcd::io
