#pragma once
// Line-by-line tokenizer for whole-file text formats (TetGen, OFF, OBJ, STL, PLY), with number
// parsing that reports the file, the line and the offending token.

#include <charconv>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace deformcd::io {

/// Reads the whole of `file`, a regular file (or a link to one), into memory. Throws InputError
/// naming the file when it cannot, or when it is a directory, FIFO, socket or device.
std::string read_whole_file(const std::filesystem::path& file);

enum class NumberParse { kOk, kNotANumber, kOutOfRange };

/// Parses the whole of `token` as a 64-bit integer. A leading '+' is allowed.
NumberParse parse_integer(std::string_view token, std::int64_t& value);

/// Parses the whole of `token` as a double with correct rounding (std::from_chars), accepting a
/// leading '+', "inf" and "nan" (validation rejects non-finite coordinates later, with the line).
/// Underflow to zero or a subnormal is accepted; overflow is kOutOfRange.
NumberParse parse_real(std::string_view token, double& value);

/// Walks a text one record at a time: a record is a line split at blanks, with '#' comments
/// (whole-line and trailing) removed when `hash_comments` is set, and blank lines skipped.
/// Errors name the file and the 1-based line of the current record.
class TextScanner {
 public:
  TextScanner(std::string_view text, std::string file, bool hash_comments = true,
              std::size_t first_line = 1);

  /// Moves to the next non-blank record. False (and no record) at the end of the text.
  bool next_record();

  [[nodiscard]] std::size_t size() const { return tokens_.size(); }
  [[nodiscard]] std::string_view token(std::size_t i) const { return tokens_[i]; }
  [[nodiscard]] std::size_t line() const { return line_; }
  [[nodiscard]] const std::string& file() const { return file_; }
  /// The whole text's size in bytes.
  [[nodiscard]] std::size_t text_size() const { return text_.size(); }
  /// Byte offset just past the current record's line (where the next line starts).
  [[nodiscard]] std::size_t offset_after_record() const { return pos_; }

  /// Token `i` as an integer of type T; throws "'x' is not an integer" / "is out of range".
  template <std::integral T>
  [[nodiscard]] T integer(std::size_t i) const {
    std::int64_t value = 0;
    const NumberParse result = parse_integer(tokens_[i], value);
    if (result == NumberParse::kNotANumber) fail_token(i, "is not an integer");
    if (result == NumberParse::kOutOfRange || !std::in_range<T>(value)) {
      fail_token(i, "is out of range");
    }
    return static_cast<T>(value);
  }

  /// Token `i` as a double; throws "'x' is not a number" / "'x' is out of range".
  [[nodiscard]] double real(std::size_t i) const;

  /// Checks a header's count of one-per-line records against the rest of the text, which holds
  /// at most (bytes + 1) / 2 non-blank lines: throws at the current record ("declares 5000000
  /// nodes, but the 120 bytes after this line hold at most 60 lines") when `count` cannot fit.
  /// Readers call it before reserving anything for `count`, so that a corrupt count fails at
  /// once; a few missing records are left to the record loop, whose error names the line
  /// where the file ends.
  void check_line_count(std::uint64_t count, const char* singular, const char* plural) const;

  /// Throws InputError at the current record's line.
  [[noreturn]] void fail(const std::string& message) const;
  /// Throws InputError at the last line read, for "file ends after ..." messages once
  /// next_record() has returned false.
  [[noreturn]] void fail_at_end(const std::string& message) const;

 private:
  [[noreturn]] void fail_token(std::size_t i, const char* what) const;

  std::string_view text_;
  std::string file_;
  bool hash_comments_;
  std::size_t pos_ = 0;        // start of the next unread line
  std::size_t next_line_ = 1;  // 1-based number of the next unread line
  std::size_t line_ = 0;       // line of the current record
  std::vector<std::string_view> tokens_;
};

}  // namespace deformcd::io
