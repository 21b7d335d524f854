#include "deformcd/error.h"

#include <utility>

namespace deformcd {

namespace {
std::string located(const std::string& source, std::size_t line, const std::string& message) {
  if (line == 0) return source + ": " + message;
  return source + ":" + std::to_string(line) + ": " + message;
}
}  // namespace

InputError::InputError(std::string source, std::size_t line, const std::string& message)
    : Error(located(source, line, message)), source_(std::move(source)), line_(line) {}

InputError::InputError(std::string source, const std::string& message)
    : InputError(std::move(source), 0, message) {}

}  // namespace deformcd
