#pragma once
// Checks made before any work, so that a long run never ends in "cannot write": every output
// path can be written and every program an option needs is on PATH. Errors name the option and
// the path as the user gave it.

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <streambuf>
#include <string>
#include <string_view>

namespace deformcd::app {

/// `file` (given with `option`, e.g. "--json") can be written: "-" (standard output); an
/// existing device, FIFO or socket that is writable (written directly); or a name (symlinks
/// followed) that can be created or replaced: its directory exists and is writable, and it is
/// not a directory. Throws Error otherwise. How each is written: io::AtomicFile.
void check_output_file(std::string_view option, const std::string& file);

/// Whether any of `outputs` (output option values) is "-", standard output.
[[nodiscard]] bool writes_stdout(std::initializer_list<std::string_view> outputs);

/// While alive, and if constructed with `move` true, sends what the command prints on std::cout
/// (its summary) to standard error, so that an output written to standard output ("-") is not
/// mixed with it. Outputs to "-" write the descriptor itself, which this leaves alone.
class SummaryOnStderr {
 public:
  explicit SummaryOnStderr(bool move);
  ~SummaryOnStderr();
  SummaryOnStderr(const SummaryOnStderr&) = delete;
  SummaryOnStderr& operator=(const SummaryOnStderr&) = delete;

 private:
  std::streambuf* previous_ = nullptr;
};

/// `dir` is a writable directory, or can be created: no file is in the way and its nearest
/// existing ancestor is a writable directory. Throws Error otherwise.
void check_output_directory(std::string_view option, const std::string& dir);

/// Creates `dir` (and its parents) if needed. Throws Error naming `option` on failure.
void create_output_directory(std::string_view option, const std::string& dir);

/// The first executable file `name` in the directories of $PATH, if any.
[[nodiscard]] std::optional<std::filesystem::path> find_on_path(std::string_view name);

/// find_on_path(program), or throws Error: "`option` `value`: needs `program`, which is not on
/// PATH (`install`)".
[[nodiscard]] std::filesystem::path require_program(std::string_view option,
                                                    const std::string& value,
                                                    std::string_view program,
                                                    std::string_view install);

}  // namespace deformcd::app
