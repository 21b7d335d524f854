#pragma once
// The tool's exit statuses, and the error for a command line that asks for something impossible.

#include "deformcd/error.h"

namespace deformcd::app {

/// 0: done. 1: the work failed (an input file missing, unreadable or malformed, an unwritable
/// output, a missing program, no GL, a simulation that blew up, methods that disagree). 2: a
/// usage error (unknown command or option, a missing argument, a bad option value), reported
/// before any work. The same in every command (docs/reliability.md, "Exit statuses").
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;

/// An option value that cannot be used (e.g. `--frames 0`), found after CLI11 parsed it;
/// main() reports it like CLI11's own errors, with exit status kExitUsage.
class UsageError : public Error {
 public:
  using Error::Error;
};

}  // namespace deformcd::app
