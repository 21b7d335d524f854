#include "tetgen/isolated_run.h"

#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "deformcd/error.h"

namespace deformcd::detail {

namespace {

int make_temp_file() {
  char path[] = "/tmp/deformcd-isolated-XXXXXX";
  const int fd = mkstemp(path);
  if (fd >= 0) unlink(path);
  return fd;
}

std::string read_all(int fd) {
  std::string data;
  if (lseek(fd, 0, SEEK_SET) != 0) return data;
  char buffer[1 << 16];
  ssize_t n = 0;
  while ((n = read(fd, buffer, sizeof buffer)) > 0)
    data.append(buffer, static_cast<size_t>(n));
  return data;
}

bool write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

IsolatedResult run_isolated(const std::function<int(std::string& output)>& work) {
  const int out_fd = make_temp_file();
  const int log_fd = make_temp_file();
  if (out_fd < 0 || log_fd < 0) {
    if (out_fd >= 0) close(out_fd);
    if (log_fd >= 0) close(log_fd);
    throw Error(std::string("cannot create temporary files for an isolated run: ") +
                std::strerror(errno));
  }
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) {
    close(out_fd);
    close(log_fd);
    throw Error(std::string("cannot fork an isolated process: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // Child: never return into the caller's code; _exit skips the parent's atexit handlers.
    dup2(log_fd, STDOUT_FILENO);
    dup2(log_fd, STDERR_FILENO);
    int status = 0;
    try {
      std::string output;
      status = work(output);
      if (!write_all(out_fd, output)) status = 120;
    } catch (...) {
      status = 121;
    }
    std::fflush(nullptr);
    _exit(status);
  }

  IsolatedResult result;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) break;
  }
  if (WIFEXITED(status)) {
    result.exit_status = WEXITSTATUS(status);
    result.ok = result.exit_status == 0;
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  result.output = read_all(out_fd);
  result.log = read_all(log_fd);
  close(out_fd);
  close(log_fd);
  return result;
}

}  // namespace deformcd::detail
