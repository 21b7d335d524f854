// Issue 34, item 5: reading a file costs its size once, and an STL whose header already shows
// the size is wrong is refused before it is read. Measured as the peak resident memory of a
// forked child doing the read (getrusage's ru_maxrss), so the test process's own heap does not
// blur it.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "deformcd/error.h"
#include "deformcd/io.h"
#include "io/io_test_support.h"
#include "io/text_scanner.h"
#include "support/sanitizers.h"

namespace deformcd {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

constexpr std::uintmax_t kMiB = 1024 * 1024;

// A file of `size` bytes, all zero but `head`, made sparse (no disk used).
fs::path sparse_file(const fs::path& file, std::uintmax_t size, std::string_view head = {}) {
  test::write_file(file, head);
  fs::resize_file(file, size);
  return file;
}

struct ChildRead {
  long peak_growth_kib = -1;  // the child's peak resident memory over what it started with
  std::string outcome;        // "ok", or the InputError's message, or "other error: ..."
};

ChildRead read_in_child(const std::function<void()>& read) {
  std::array<int, 2> fds{};
  EXPECT_EQ(::pipe(fds.data()), 0);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    rusage before{};
    ::getrusage(RUSAGE_SELF, &before);
    std::string outcome = "ok";
    try {
      read();
    } catch (const InputError& e) {
      outcome = e.what();
    } catch (const std::exception& e) {
      outcome = std::string("other error: ") + e.what();
    }
    rusage after{};
    ::getrusage(RUSAGE_SELF, &after);
    const std::string report = std::to_string(after.ru_maxrss - before.ru_maxrss) + " " + outcome;
    (void)!::write(fds[1], report.data(), report.size());
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string report;
  std::array<char, 4096> buffer{};
  for (ssize_t n; (n = ::read(fds[0], buffer.data(), buffer.size())) > 0;)
    report.append(buffer.data(), static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ChildRead r;
  const std::size_t space = report.find(' ');
  if (space == std::string::npos) return r;
  r.peak_growth_kib = std::stol(report.substr(0, space));
  r.outcome = report.substr(space + 1);
  return r;
}

TEST(InputMemory, AWholeFileIsHeldOnce) {
#ifdef DEFORMCD_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine blur resident memory";
#endif
  TempDir dir;
  constexpr std::uintmax_t kSize = 64 * kMiB;
  const fs::path file = sparse_file(dir / "big.off", kSize);
  const ChildRead r = read_in_child([&] {
    const std::string data = io::read_whole_file(file);
    if (data.size() != kSize) throw std::runtime_error("read " + std::to_string(data.size()));
  });
  EXPECT_EQ(r.outcome, "ok");
  // One copy is 64 MiB; before the fix the last chunk's read reallocated it, holding two.
  EXPECT_LT(r.peak_growth_kib, static_cast<long>(kSize / 1024 * 5 / 4)) << "KiB";
  EXPECT_GT(r.peak_growth_kib, static_cast<long>(kSize / 1024 * 3 / 4)) << "KiB";
}

TEST(InputMemory, AnStlOfTheWrongSizeIsRefusedBeforeItIsRead) {
#ifdef DEFORMCD_UNDER_ASAN
  GTEST_SKIP() << "AddressSanitizer's shadow memory and quarantine blur resident memory";
#endif
  TempDir dir;
  constexpr std::uintmax_t kSize = 200 * kMiB;  // the random 200 MB .stl
  std::string head(84, '\x01');  // no "solid", a binary count of 0x01010101 triangles
  const fs::path file = sparse_file(dir / "random.stl", kSize, head);
  const ChildRead r = read_in_child([&] { (void)read_surface(file); });
  EXPECT_EQ(r.outcome, file.string() +
                           ": binary STL header announces 16843009 triangles (842150534 bytes), "
                           "but the file has 209715200 bytes: truncated or not an STL file");
  EXPECT_LT(r.peak_growth_kib, 16 * 1024) << "KiB";
}

}  // namespace
}  // namespace deformcd
