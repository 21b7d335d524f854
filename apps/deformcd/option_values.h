#pragma once
// Options that mean the same in every command, registered in one place so that their names,
// help and checks agree: --frames (the run's length) and --broadphase. And small helpers for
// checking option values and wording counts.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace deformcd::app {

/// `--frames N`: the run's length (default: the scene's settings.frames); the bodies' paths span
/// exactly this many frames.
void add_frames_option(CLI::App* command, std::optional<int>& frames);

/// `--broadphase METHOD` (default: the scene's collision.broadphase); `none` only when
/// `none_ok`. An unknown name is a usage error listing the valid ones.
void add_broadphase_option(CLI::App* command, std::optional<std::string>& broadphase, bool none_ok);

/// Throws UsageError "`option` must be at least `minimum`, got `value`".
void check_at_least(const char* option, long value, long minimum);

/// `--threads T`: the library's rule (deformcd::check_thread_count: 0 to kMaxThreads) as a
/// UsageError with the library's message.
void check_threads_option(long threads);

/// The most substeps (frames x substeps) a run takes unless the environment sets
/// DEFORMCD_LONG_RUN=1: a hundred times the longest shipped scene's (9,600). `substeps: 1e9` or
/// `--frames 2000000000` would otherwise run for days with no word said. (An environment
/// variable, not an option: the command line's options are the README's synopsis.)
inline constexpr long long kMaxRunSubsteps = 1'000'000;

/// Throws UsageError naming the run's length unless frames x substeps <= kMaxRunSubsteps or
/// DEFORMCD_LONG_RUN=1 lifts the limit.
void check_run_length(long long frames, long long substeps);

/// "1 body", "2 bodies".
[[nodiscard]] std::string count_of(std::uint64_t n, const char* one, const char* many);

}  // namespace deformcd::app
