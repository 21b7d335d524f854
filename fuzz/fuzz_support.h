#pragma once
// What every fuzz target checks, whatever the reader: bad input may only end in an InputError
// whose message starts with the file's name; anything else (another exception, a sanitizer
// report, a hang, a leak, an allocation past libFuzzer's -malloc_limit_mb) is a finding.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "deformcd/error.h"

namespace deformcd::fuzz {

/// Stops the process so that libFuzzer saves the input as a crash.
[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

/// DEFORMCD_FUZZ_VERBOSE=1 prints each input's outcome (when replaying a corpus or a finding).
inline bool verbose() {
  static const bool on = std::getenv("DEFORMCD_FUZZ_VERBOSE") != nullptr;
  return on;
}

/// Runs `read`; true when it returned, false when it threw an InputError about a file whose
/// name starts with `file` (the TetGen target reads three).
template <class Read>
bool reads_or_rejects(Read&& read, std::string_view file) {
  try {
    read();
    if (verbose()) std::fprintf(stderr, "read: %.*s\n", static_cast<int>(file.size()), file.data());
    return true;
  } catch (const InputError& e) {
    const std::string_view what = e.what();
    if (!e.source().starts_with(file) || !what.starts_with(e.source())) {
      finding("an InputError that does not name " + std::string(file) + ": " + std::string(what));
    }
    if (verbose()) std::fprintf(stderr, "rejected: %s\n", e.what());
    return false;
  } catch (const std::exception& e) {
    finding(std::string("an exception other than InputError: ") + e.what());
  } catch (...) {
    finding("an exception that is not a std::exception");
  }
}

}  // namespace deformcd::fuzz
