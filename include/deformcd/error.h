#pragma once
/// \file error.h
/// Errors thrown at deformcd's boundaries (files, command line, GL set-up).
/// Every message states the violated contract and, for input, where it was violated.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace deformcd {

/// Base of every error deformcd throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input data: a malformed file, an index out of range, a degenerate element...
/// what() reads "FILE:LINE: message" (or "FILE: message" when no line applies).
class InputError : public Error {
 public:
  /// An error at `line` (1-based) of file `source`.
  InputError(std::string source, std::size_t line, const std::string& message);
  /// An error in `source` (a file, or a name such as "mesh 1") where no line applies.
  InputError(std::string source, const std::string& message);

  /// The file (or description of the in-memory source) the error is about.
  [[nodiscard]] const std::string& source() const noexcept { return source_; }
  /// 1-based line number, or 0 when the error is not tied to a line.
  [[nodiscard]] std::size_t line() const noexcept { return line_; }

 private:
  std::string source_;
  std::size_t line_ = 0;
};

/// A GL 4.3 compute context could not be had, or GL reported an error.
class GlError : public Error {
 public:
  using Error::Error;
};

}  // namespace deformcd
