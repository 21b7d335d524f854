#include "deformcd/error.h"

#include <utility>

namespace deformcd {

namespace {

// Control characters from an input file must not reach a terminal (an escape sequence in an OFF
// header could retitle it, or worse): each becomes \xNN. C0 controls, DEL and the C1 controls
// (U+0080..U+009F, 0xC2 0x80..0x9F in UTF-8) are escaped; other bytes are left as they are.
std::string printable(const std::string& text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  const auto escape = [&out](unsigned char c) {
    out += "\\x";
    out += kHex[c >> 4];
    out += kHex[c & 0xf];
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      escape(c);
    } else if (c == 0xc2 && i + 1 < text.size() &&
               static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
      escape(static_cast<unsigned char>(text[++i]));
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string located(const std::string& source, std::size_t line, const std::string& message) {
  if (line == 0) return printable(source + ": " + message);
  return printable(source + ":" + std::to_string(line) + ": " + message);
}

}  // namespace

InputError::InputError(std::string source, std::size_t line, const std::string& message)
    : Error(located(source, line, message)), source_(std::move(source)), line_(line) {}

InputError::InputError(std::string source, const std::string& message)
    : InputError(std::move(source), 0, message) {}

}  // namespace deformcd
