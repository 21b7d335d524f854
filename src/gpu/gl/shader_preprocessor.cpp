#include "gpu/gl/shader_preprocessor.h"

#include <algorithm>
#include <optional>
#include <string>

#include "deformcd/error.h"
#include "gpu/gl/shader_library.h"

namespace deformcd::gl {

namespace {

std::string_view trim_left(std::string_view s) {
  const std::size_t start = s.find_first_not_of(" \t\r");
  return start == std::string_view::npos ? std::string_view{} : s.substr(start);
}

// The directive's name when `line` is a preprocessor directive ("version", "include"...).
std::string_view directive_of(std::string_view line) {
  line = trim_left(line);
  if (line.empty() || line.front() != '#') return {};
  line = trim_left(line.substr(1));
  return line.substr(0, line.find_first_of(" \t\"<"));
}

// The quoted name of `#include "name"`, or nullopt when the line is malformed.
std::optional<std::string> include_target(std::string_view line) {
  const std::size_t open = line.find('"');
  const std::size_t close = open == std::string_view::npos ? open : line.find('"', open + 1);
  if (close == std::string_view::npos || close == open + 1) return std::nullopt;
  if (!trim_left(line.substr(close + 1)).empty()) return std::nullopt;
  return std::string(line.substr(open + 1, close - open - 1));
}

class Expander {
 public:
  explicit Expander(const ShaderLibrary& library) : library_(library) {}

  PreprocessedShader run(std::string_view name) {
    expand(name, true);
    return std::move(out_);
  }

 private:
  void expand(std::string_view name, bool is_root) {
    const auto index = static_cast<std::uint32_t>(out_.files.size());
    out_.files.emplace_back(name);
    const std::string source = library_.source(name);
    const std::string file(name);
    bool seen_version = false;
    std::uint32_t line_number = 0;
    std::size_t pos = 0;
    while (pos < source.size()) {
      std::size_t end = source.find('\n', pos);
      if (end == std::string::npos) end = source.size();
      const std::string_view line(source.data() + pos, end - pos);
      pos = end + 1;
      ++line_number;
      const std::string_view directive = directive_of(line);
      if (directive == "version") {
        if (!is_root) {
          throw GlError(file + ":" + std::to_string(line_number) +
                        ": an included file must not have a #version line");
        }
        seen_version = true;
        append_line(line, {index, line_number});
        continue;
      }
      if (directive != "include") {
        append_line(line, {index, line_number});
        continue;
      }
      if (is_root && !seen_version) {
        throw GlError(file + ":" + std::to_string(line_number) +
                      ": #include before the #version line");
      }
      const std::optional<std::string> target = include_target(line);
      if (!target) {
        throw GlError(file + ":" + std::to_string(line_number) +
                      ": malformed #include; write #include \"path/under/shaders.glsl\"");
      }
      if (std::find(out_.files.begin(), out_.files.end(), *target) != out_.files.end()) {
        append_line("// #include \"" + *target + "\" (already included)", {index, line_number});
        continue;
      }
      try {
        expand(*target, false);
      } catch (const GlError& e) {
        throw GlError(file + ":" + std::to_string(line_number) + ": in #include \"" + *target +
                      "\": " + e.what());
      }
    }
    if (is_root && !seen_version) {
      throw GlError(file + ": no #version line (it must come first, before any #include)");
    }
  }

  void append_line(std::string_view line, SourceLine origin) {
    out_.text += line;
    out_.text += '\n';
    out_.origins.push_back(origin);
  }

  const ShaderLibrary& library_;
  PreprocessedShader out_;
};

}  // namespace

PreprocessedShader preprocess_shader(std::string_view name, const ShaderLibrary& library) {
  return Expander(library).run(name);
}

}  // namespace deformcd::gl
