#pragma once
// Runs the deformcd tool (or any shell command) as a user would, capturing its output.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace deformcd::test {

struct CliRun {
  int status = -1;     // exit status, -1 when killed or not run
  std::string output;  // stdout and stderr together
};

// Runs `command` through /bin/sh with stderr merged into stdout.
inline CliRun run_shell(const std::string& command) {
  CliRun r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Environment for a deformcd that draws: in sanitizer builds, no leak check at exit, since
// Mesa's llvmpipe leaks once on the first draw in a library it unloads (see
// first_draw_leak_guard.cpp; in-process tests check our own allocations). Other ASAN_OPTIONS
// are kept; elsewhere the variable is ignored.
inline const char* kDrawingEnvironment =
    "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\"";

// Runs `deformcd ARGS` from the source directory (scenes/ is relative to it), with
// kDrawingEnvironment and then `environment` (VAR=value... or a command prefix like env -u).
inline CliRun run_cli(const std::string& args, const std::string& environment = "") {
  return run_shell("cd " + std::string(DEFORMCD_SOURCE_DIR) + " && " + kDrawingEnvironment + " " +
                   environment + " " + DEFORMCD_CLI + " " + args);
}

}  // namespace deformcd::test
