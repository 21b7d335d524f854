#pragma once
// Runs a function in a forked child process and brings back its output bytes and its stdout.
// TetGen's library can crash (segmentation fault on some self-intersecting inputs) or exit();
// in a child, that becomes an error message instead of the end of the caller's process.

#include <functional>
#include <string>

namespace deformcd::detail {

struct IsolatedResult {
  bool ok = false;       ///< the child returned normally with exit status 0
  int exit_status = -1;  ///< child's exit status when it exited, else -1
  int signal = 0;        ///< signal that killed the child, else 0
  std::string output;    ///< bytes the child's function returned
  std::string log;       ///< what the child printed on stdout / stderr
};

/// Forks; the child runs `work` (whose returned bytes are passed back) with stdout and stderr
/// captured, and exits with `work`'s status. Throws deformcd::Error if the fork fails.
/// `work` returns 0 on success; non-zero statuses are passed through as exit_status.
IsolatedResult run_isolated(const std::function<int(std::string& output)>& work);

}  // namespace deformcd::detail
