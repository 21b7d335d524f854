#include "gpu/gl/shader_log.h"

#include <cctype>
#include <string>

namespace deformcd::gl {

namespace {

std::size_t count_digits(std::string_view s, std::size_t from) {
  std::size_t n = 0;
  while (from + n < s.size() && std::isdigit(static_cast<unsigned char>(s[from + n])) != 0)
    ++n;
  return n;
}

// Rewrites one line of the log; see shader_log.h for the formats.
std::string map_line(std::string_view line, const PreprocessedShader& shader) {
  std::size_t start = 0;
  for (std::string_view severity : {"ERROR: ", "WARNING: "}) {
    if (line.starts_with(severity)) start = severity.size();
  }
  // "0" then ":" or "(", then the line number.
  if (count_digits(line, start) != 1 || line[start] != '0' || start + 2 >= line.size() ||
      (line[start + 1] != ':' && line[start + 1] != '(')) {
    return std::string(line);
  }
  const std::size_t number_start = start + 2;
  const std::size_t digits = count_digits(line, number_start);
  if (digits == 0 || digits > 9) return std::string(line);
  const std::size_t number = std::stoul(std::string(line.substr(number_start, digits)));
  if (number == 0 || number > shader.origins.size()) return std::string(line);
  const SourceLine& origin = shader.origins[number - 1];
  return std::string(line.substr(0, start)) + shader.files[origin.file] + line[start + 1] +
         std::to_string(origin.line) + std::string(line.substr(number_start + digits));
}

}  // namespace

std::string map_driver_log(std::string_view log, const PreprocessedShader& shader) {
  std::string out;
  std::size_t pos = 0;
  while (pos < log.size()) {
    std::size_t end = log.find('\n', pos);
    const bool has_newline = end != std::string_view::npos;
    if (!has_newline) end = log.size();
    out += map_line(log.substr(pos, end - pos), shader);
    if (has_newline) out += '\n';
    pos = end + 1;
  }
  return out;
}

}  // namespace deformcd::gl
