#include "output_paths.h"

#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <sstream>
#include <system_error>

#include "deformcd/error.h"
#include "deformcd/io.h"

namespace deformcd::app {

namespace fs = std::filesystem;

namespace {

std::string named(std::string_view option, const std::string& path) {
  return std::string(option) + " " + path;
}

// The directory a new entry `path` would be created in ("." for a bare name).
fs::path directory_of(const fs::path& path) {
  const fs::path parent = path.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

bool writable_directory(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) && ::access(dir.c_str(), W_OK | X_OK) == 0;
}

}  // namespace

void check_output_file(std::string_view option, const std::string& file) {
  if (file == "-") return;  // standard output
  std::error_code ec;
  if (file.empty() || fs::path(file).filename().empty() || fs::is_directory(file, ec)) {
    throw Error(named(option, file) + ": is a directory; give a file name");
  }
  // A device, FIFO or socket (links followed) is written directly and needs only to be
  // writable; otherwise what is replaced is the links' final target (io::AtomicFile).
  const fs::file_status status = fs::status(file, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    if (::access(file.c_str(), W_OK) != 0) throw Error(named(option, file) + ": is not writable");
    return;
  }
  const fs::path path = follow_symlinks(file);
  const fs::path dir = directory_of(path);
  if (!fs::exists(dir, ec)) {
    throw Error(named(option, file) + ": the directory " + dir.string() +
                " does not exist (create it first)");
  }
  if (!fs::is_directory(dir, ec)) {
    throw Error(named(option, file) + ": " + dir.string() + " is not a directory");
  }
  if (!writable_directory(dir)) {
    throw Error(named(option, file) + ": the directory " + dir.string() + " is not writable");
  }
  if (fs::exists(path, ec) && ::access(path.c_str(), W_OK) != 0) {
    throw Error(named(option, file) + ": the file exists and is not writable");
  }
}

void check_output_directory(std::string_view option, const std::string& dir) {
  std::error_code ec;
  const fs::path path(dir);
  if (dir.empty()) throw Error(std::string(option) + ": give a directory");
  if (fs::exists(path, ec)) {
    if (!fs::is_directory(path, ec)) {
      throw Error(named(option, dir) +
                  ": cannot create the output directory (a file of that name is in the way)");
    }
    if (!writable_directory(path))
      throw Error(named(option, dir) + ": the directory is not writable");
    return;
  }
  // Walk up to the nearest existing ancestor: it must be a writable directory.
  fs::path ancestor = fs::absolute(path, ec).parent_path();
  while (!ancestor.empty() && !fs::exists(ancestor, ec) && ancestor != ancestor.root_path()) {
    ancestor = ancestor.parent_path();
  }
  if (!fs::is_directory(ancestor, ec)) {
    throw Error(named(option, dir) + ": cannot create the output directory (" + ancestor.string() +
                " is a file)");
  }
  if (!writable_directory(ancestor)) {
    throw Error(named(option, dir) + ": cannot create the output directory (" + ancestor.string() +
                " is not writable)");
  }
}

void create_output_directory(std::string_view option, const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw Error(named(option, dir) + ": cannot create the output directory (" +
                (ec ? ec.message() : std::string("a file of that name is in the way")) + ")");
  }
}

bool writes_stdout(std::initializer_list<std::string_view> outputs) {
  for (std::string_view output : outputs) {
    if (output == "-") return true;
  }
  return false;
}

SummaryOnStderr::SummaryOnStderr(bool move) {
  if (move) previous_ = std::cout.rdbuf(std::cerr.rdbuf());
}

SummaryOnStderr::~SummaryOnStderr() {
  if (previous_ != nullptr) std::cout.rdbuf(previous_);
}

std::optional<fs::path> find_on_path(std::string_view name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::istringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;  // POSIX says "the current directory"; we do not search it
    const fs::path candidate = fs::path(dir) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return std::nullopt;
}

fs::path require_program(std::string_view option, const std::string& value,
                         std::string_view program, std::string_view install) {
  if (std::optional<fs::path> found = find_on_path(program)) return *found;
  throw Error(named(option, value) + ": needs " + std::string(program) +
              ", and there is none on PATH (" + std::string(install) + ")");
}

}  // namespace deformcd::app
