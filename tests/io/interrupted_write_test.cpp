// Files appear whole or not at all even when the writing process is killed: a child process
// opens a StreamedFileWriter (what `deformcd run --contacts` streams each frame into), writes,
// and is killed by SIGINT (Ctrl-C), SIGTERM or SIGKILL before committing. The directory must
// then hold nothing new: no target, no temporary. Before O_TMPFILE, each kill left a hidden
// ".contacts.jsonl.tmp-PID-0" behind. Outputs written by a child process (ffmpeg) through
// StreamedFileWriter::path_for_child_process() are covered too.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io/io_test_support.h"

namespace deformcd {
namespace {

using test::TempDir;

const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGKILL";
}

// Forks a child that runs `write` (which must not return before it wants to be killed), waits
// until it says it is ready, kills it with `sig` and checks that it died of it.
template <class Write>
void kill_while_writing(int sig, Write&& write) {
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // As a CLI in a terminal has them: a shell without job control (CI scripts) starts
    // background commands with SIGINT ignored, and this child inherits that.
    ::signal(SIGINT, SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::close(ready[0]);
    write([fd = ready[1]] {
      const char byte = 'r';
      (void)!::write(fd, &byte, 1);
      for (;;)
        ::pause();
    });
    ::_exit(0);  // not reached
  }
  ::close(ready[1]);
  char byte = 0;
  ASSERT_EQ(::read(ready[0], &byte, 1), 1) << "the child died before it was ready";
  ::close(ready[0]);
  ASSERT_EQ(::kill(pid, sig), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
  EXPECT_EQ(WTERMSIG(status), sig);
}

class InterruptedWrite : public ::testing::TestWithParam<int> {};

TEST_P(InterruptedWrite, LeavesNoFileAndNoTemporary) {
  TempDir dir;
  kill_while_writing(GetParam(), [&](auto wait_for_the_signal) {
    StreamedFileWriter out(dir / "contacts.jsonl");
    out.append("{\"frame\":0,\"contacts\":[]}\n");
    out.append(std::string(1 << 20, ' '));  // past stdio's buffer: bytes reach the file
    wait_for_the_signal();
  });
  EXPECT_EQ(dir.files(), std::vector<std::string>{}) << signal_name(GetParam());
}

TEST_P(InterruptedWrite, LeavesAnExistingTargetUntouched) {
  TempDir dir;
  test::write_file(dir / "positions.json", "old\n");
  kill_while_writing(GetParam(), [&](auto wait_for_the_signal) {
    io::AtomicFile out(dir / "positions.json");
    out.write(std::string(1 << 20, 'x'));
    wait_for_the_signal();
  });
  EXPECT_EQ(dir.files(), std::vector<std::string>{"positions.json"}) << signal_name(GetParam());
  EXPECT_EQ(test::read_text(dir / "positions.json"), "old\n");
}

TEST_P(InterruptedWrite, AfterTheCommitTheFileIsWhole) {
  TempDir dir;
  kill_while_writing(GetParam(), [&](auto wait_for_the_signal) {
    StreamedFileWriter out(dir / "contacts.jsonl");
    out.append("frame 0\n");
    out.append("frame 1\n");
    out.commit();
    wait_for_the_signal();
  });
  EXPECT_EQ(dir.files(), std::vector<std::string>{"contacts.jsonl"}) << signal_name(GetParam());
  EXPECT_EQ(test::read_text(dir / "contacts.jsonl"), "frame 0\nframe 1\n");
}

TEST_P(InterruptedWrite, AnOutputOfAChildProcessLeavesNothingEither) {
  // As `render --video` would have ffmpeg write the video: through path_for_child_process().
  TempDir dir;
  kill_while_writing(GetParam(), [&](auto wait_for_the_signal) {
    StreamedFileWriter video(dir / "run.mp4");
    const std::string command = "printf 'partial video' > '" + video.path_for_child_process() + "'";
    if (std::system(command.c_str()) != 0) ::_exit(1);
    wait_for_the_signal();
  });
  EXPECT_EQ(dir.files(), std::vector<std::string>{}) << signal_name(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Signals, InterruptedWrite, ::testing::Values(SIGINT, SIGTERM, SIGKILL),
                         [](const ::testing::TestParamInfo<int>& p) {
                           return std::string(signal_name(p.param));
                         });

}  // namespace
}  // namespace deformcd
