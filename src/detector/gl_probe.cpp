#include "detector/gl_probe.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>

#include "detector/backend_choice.h"

namespace deformcd {

namespace {

// In the child: one status byte ('R' renderer, 'N' no GL) then the text, then _exit (no
// destructors, no atexit handlers of the parent's libraries, no flushing its stdio buffers).
[[noreturn]] void run_probe_child(int out) {
  char status = 'N';
  std::string text;
  try {
    text = headless_gl_renderer();
    status = 'R';
  } catch (const std::exception& e) {
    text = e.what();
  } catch (...) {
    text = "an unknown error while creating the context";
  }
  const std::string message = status + text;
  std::size_t written = 0;
  while (written < message.size()) {
    const ssize_t n = ::write(out, message.data() + written, message.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    written += static_cast<std::size_t>(n);
  }
  ::_exit(0);
}

// Reads everything from `in` until the child closes it or `deadline` passes; false on timeout.
bool read_answer(int in, std::chrono::steady_clock::time_point deadline, std::string& answer) {
  std::array<char, 4096> buffer{};
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                          deadline - std::chrono::steady_clock::now())
                          .count();
    if (left <= 0) return false;
    pollfd p{in, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return false;
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;  // the child closed its end: exited or died
    answer.append(buffer.data(), static_cast<std::size_t>(n));
  }
}

}  // namespace

GlProbe probe_gl_in_child(int timeout_ms) {
  GlProbe probe;
  if (!gl_backend_built()) return probe;  // nothing to look for: kNotRun
  std::array<int, 2> fds{};
  if (::pipe2(fds.data(), O_CLOEXEC) != 0) return probe;
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return probe;
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_probe_child(fds[1]);
  }
  ::close(fds[1]);
  std::string answer;
  const bool answered = read_answer(
      fds[0], std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms), answer);
  ::close(fds[0]);
  if (!answered) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!answered) {
    probe.outcome = GlProbe::Outcome::kCrashed;
    probe.text = "it did not answer in " + std::to_string(timeout_ms / 1000) + " s";
  } else if (WIFSIGNALED(status)) {
    probe.outcome = GlProbe::Outcome::kCrashed;
    probe.text = std::string("the driver died of signal ") + std::to_string(WTERMSIG(status)) +
                 " (" + ::strsignal(WTERMSIG(status)) + ")";
  } else if (answer.empty() || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    probe.outcome = GlProbe::Outcome::kCrashed;
    probe.text = "it ended without an answer (exit status " +
                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
  } else {
    probe.outcome = answer[0] == 'R' ? GlProbe::Outcome::kRenderer : GlProbe::Outcome::kNoGl;
    probe.text = answer.substr(1);
  }
  return probe;
}

}  // namespace deformcd
