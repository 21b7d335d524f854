#pragma once
// Checks made before any work, so that a long run never ends in "cannot write": every output
// path can be written and every program an option needs is on PATH. Errors name the option and
// the path as the user gave it.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace deformcd::app {

/// `file` (given with `option`, e.g. "--json") can be created or replaced: its directory exists
/// and is writable, and `file` is not a directory. Throws Error otherwise.
void check_output_file(std::string_view option, const std::string& file);

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
