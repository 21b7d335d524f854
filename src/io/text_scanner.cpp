#include "io/text_scanner.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "deformcd/error.h"

namespace deformcd::io {

namespace {

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

// from_chars rejects the '+' that C's strtod (and so TetGen) accepts.
std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

// from_chars reports result_out_of_range for both overflow and underflow; only the exponent's
// sign tells them apart. Underflow means the nearest double is zero, which is a fine coordinate.
bool has_negative_exponent(std::string_view token) {
  const std::size_t e = token.find_last_of("eE");
  return e != std::string_view::npos && e + 1 < token.size() && token[e + 1] == '-';
}

}  // namespace

std::string read_whole_file(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  if (std::filesystem::is_directory(status)) {
    throw InputError(file.string(), "is a directory, not a file");
  }
  // A FIFO, a socket or a device (/dev/zero) could block or never end: memory is bounded by
  // the input only when the input is a file.
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    throw InputError(file.string(), "is not a regular file (a FIFO, socket or device)");
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) throw InputError(file.string(), std::string("cannot open: ") + std::strerror(errno));

  // Read into a buffer of the file's size, and only then look for more: a chunk read past a
  // buffer that was exactly full would reallocate it, holding two copies (twice the file) at once.
  std::string data;
  const auto size_hint = std::filesystem::file_size(file, ec);
  if (!ec) {
    data.resize(static_cast<std::size_t>(size_hint));
    data.resize(std::fread(data.data(), 1, data.size(), f.get()));
  }
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  std::string chunk(kChunk, '\0');
  for (;;) {  // a file that grew since its size was read, or one whose size is unknown
    const std::size_t got = std::fread(chunk.data(), 1, kChunk, f.get());
    data.append(chunk.data(), got);
    if (got < kChunk) break;
  }
  if (std::ferror(f.get())) {
    throw InputError(file.string(), std::string("read error: ") + std::strerror(errno));
  }
  return data;
}

NumberParse parse_integer(std::string_view token, std::int64_t& value) {
  token = without_plus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ptr != end || ec == std::errc::invalid_argument) return NumberParse::kNotANumber;
  return ec == std::errc() ? NumberParse::kOk : NumberParse::kOutOfRange;
}

NumberParse parse_real(std::string_view token, double& value) {
  token = without_plus(token);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ptr != end || ec == std::errc::invalid_argument) return NumberParse::kNotANumber;
  if (ec == std::errc::result_out_of_range) {
    if (!has_negative_exponent(token)) return NumberParse::kOutOfRange;
    value = token[0] == '-' ? -0.0 : 0.0;
  }
  return NumberParse::kOk;
}

TextScanner::TextScanner(std::string_view text, std::string file, bool hash_comments,
                         std::size_t first_line)
    : text_(text), file_(std::move(file)), hash_comments_(hash_comments), next_line_(first_line) {}

bool TextScanner::next_record() {
  tokens_.clear();
  while (pos_ < text_.size()) {
    const std::size_t newline = text_.find('\n', pos_);
    const std::size_t line_end = newline == std::string_view::npos ? text_.size() : newline;
    std::string_view content = text_.substr(pos_, line_end - pos_);
    pos_ = newline == std::string_view::npos ? text_.size() : newline + 1;
    line_ = next_line_++;
    if (hash_comments_) content = content.substr(0, content.find('#'));

    std::size_t i = 0;
    while (i < content.size()) {
      while (i < content.size() && is_blank(content[i])) {
        ++i;
      }
      const std::size_t start = i;
      while (i < content.size() && !is_blank(content[i])) {
        ++i;
      }
      if (i > start) tokens_.push_back(content.substr(start, i - start));
    }
    if (!tokens_.empty()) return true;
  }
  return false;
}

double TextScanner::real(std::size_t i) const {
  double value = 0;
  switch (parse_real(tokens_[i], value)) {
    case NumberParse::kOk:
      return value;
    case NumberParse::kNotANumber:
      fail_token(i, "is not a number");
    case NumberParse::kOutOfRange:
      break;
  }
  fail_token(i, "is out of range");
}

void TextScanner::check_line_count(std::uint64_t count, const char* singular,
                                   const char* plural) const {
  // Each non-blank line takes at least one character and a newline (the last one none).
  const std::uint64_t bytes = text_.size() - pos_;
  const std::uint64_t room = (bytes + 1) / 2;
  if (count > room) {
    fail("declares " + std::to_string(count) + " " + (count == 1 ? singular : plural) +
         ", but the " + std::to_string(bytes) + " bytes after this line hold at most " +
         std::to_string(room) + " lines: a wrong count or a truncated file");
  }
}

void TextScanner::fail(const std::string& message) const {
  throw InputError(file_, line_, message);
}

void TextScanner::fail_at_end(const std::string& message) const {
  // Called once next_record() has returned false, so every line has been consumed.
  throw InputError(file_, std::max<std::size_t>(next_line_ - 1, 1), message);
}

void TextScanner::fail_token(std::size_t i, const char* what) const {
  fail("'" + std::string(tokens_[i]) + "' " + what);
}

}  // namespace deformcd::io
