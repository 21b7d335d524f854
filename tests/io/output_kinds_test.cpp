// Every kind of path an output can be pointed at (issue 34, item 1): "-" is standard output, a
// device, FIFO or socket is written directly and never replaced, a symlink is followed and its
// target replaced (the link kept), and a replaced file keeps its permission bits.

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/atomic_file.h"
#include "io/io_test_support.h"

namespace deformcd {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(OutputKinds, AFifoIsWrittenThroughAndStaysAFifo) {
  TempDir dir;
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_all(fifo); });
  write_file_atomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(OutputKinds, AStreamedFileReachesAFifo) {
  TempDir dir;
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_all(fifo); });
  {
    StreamedFileWriter out(fifo);
    out.append("frame 0\n");
    out.append("frame 1\n");
    out.commit();
  }
  reader.join();
  EXPECT_EQ(received, "frame 0\nframe 1\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

// A copy of a character device (1,3 is null, 1,7 is full) in `dir`: the test must not risk
// the real /dev/null, which a rename as root would replace for every process on the machine.
// Empty when this process may not make device nodes (not root, or no CAP_MKNOD).
fs::path device_copy(const TempDir& dir, const char* name, unsigned minor) {
  const fs::path node = dir / name;
  if (::mknod(node.c_str(), S_IFCHR | 0666, ::makedev(1, minor)) != 0) return {};
  return node;
}

TEST(OutputKinds, ADeviceStaysADevice) {
  TempDir dir;
  const fs::path null = device_copy(dir, "null", 3);
  if (null.empty()) GTEST_SKIP() << "cannot make a device node here (not root)";
  write_file_atomically(null, "discarded\n");
  struct stat st {};
  ASSERT_EQ(::stat(null.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  EXPECT_EQ(dir.files(), std::vector<std::string>{"null"});
}

TEST(OutputKinds, AFullDeviceIsReportedAndStaysADevice) {
  TempDir dir;
  const fs::path full = device_copy(dir, "full", 7);
  if (full.empty()) GTEST_SKIP() << "cannot make a device node here (not root)";
  try {
    write_file_atomically(full, "no room\n");
    FAIL() << "writing a full device succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
  struct stat st {};
  ASSERT_EQ(::stat(full.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
}

TEST(OutputKinds, ASymlinkIsFollowedAndItsTargetReplaced) {
  TempDir dir;
  fs::create_directories(dir / "real");
  write_file_atomically(dir / "real" / "out.json", "old\n");
  fs::create_symlink("real/out.json", dir / "link.json");
  fs::create_symlink("link.json", dir / "link2.json");  // a link to a link
  write_file_atomically(dir / "link2.json", "new\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  EXPECT_TRUE(fs::is_symlink(dir / "link2.json"));
  EXPECT_EQ(read_all(dir / "real" / "out.json"), "new\n");
  // The temporary was made in the target's directory, and nothing is left beside the link.
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"link.json", "link2.json", "real"}));
}

TEST(OutputKinds, ADanglingSymlinkCreatesItsTarget) {
  TempDir dir;
  fs::create_symlink("made.txt", dir / "link.txt");
  write_file_atomically(dir / "link.txt", "made\n");
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(read_all(dir / "made.txt"), "made\n");
}

TEST(OutputKinds, ASymlinkLoopIsReported) {
  TempDir dir;
  fs::create_symlink("b", dir / "a");
  fs::create_symlink("a", dir / "b");
  EXPECT_THROW(write_file_atomically(dir / "a", "x"), Error);
}

TEST(OutputKinds, AReplacedFileKeepsItsMode) {
  TempDir dir;
  const fs::path file = dir / "secret.json";
  write_file_atomically(file, "old\n");
  ASSERT_EQ(::chmod(file.c_str(), 0600), 0);
  write_file_atomically(file, "new\n");
  struct stat st {};
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600u);
  EXPECT_EQ(read_all(file), "new\n");

  // And through StreamedFileWriter, with a mode no umask gives.
  ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
  StreamedFileWriter out(file);
  out.append("streamed\n");
  out.commit();
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
}

TEST(OutputKinds, DashIsStandardOutput) {
  TempDir dir;
  const fs::path captured = dir / "stdout.txt";
  std::fflush(stdout);
  const int saved = ::dup(STDOUT_FILENO);
  const int file = ::open(captured.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(file, 0);
  ASSERT_EQ(::dup2(file, STDOUT_FILENO), STDOUT_FILENO);
  ::close(file);
  write_file_atomically("-", "to stdout\n");
  {
    StreamedFileWriter out("-");
    out.append("streamed\n");
    out.commit();
  }
  ::dup2(saved, STDOUT_FILENO);
  ::close(saved);
  EXPECT_EQ(read_all(captured), "to stdout\nstreamed\n");
  EXPECT_FALSE(fs::exists("-"));
}

TEST(OutputKinds, KindIsDecidedByWhatThePathNames) {
  TempDir dir;
  io::AtomicFile regular(dir / "a.txt");
  regular.write("x");
  EXPECT_EQ(regular.kind(), io::AtomicFile::Kind::kReplaced);
  io::AtomicFile device("/dev/null");  // written directly, whoever runs the test
  device.write("x");
  ASSERT_EQ(device.kind(), io::AtomicFile::Kind::kDirect);
  device.commit();
}

}  // namespace
}  // namespace deformcd
