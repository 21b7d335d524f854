#include "io/atomic_file.h"

#include "deformcd/io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "deformcd/error.h"

namespace deformcd::io {

namespace {

[[noreturn]] void fail(const std::filesystem::path& target, const std::string& what) {
  throw Error("cannot write " + target.string() + ": " + what);
}

// Unique within this process by the counter and across processes by the pid; O_EXCL and link()
// refuse to reuse a name that exists anyway.
std::filesystem::path temporary_name_for(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  const std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(getpid()) +
                           "-" + std::to_string(counter++);
  return target.parent_path() / name;
}

std::string proc_fd_path(int fd) {
  return "/proc/self/fd/" + std::to_string(fd);
}

}  // namespace

}  // namespace deformcd::io

namespace deformcd {

std::filesystem::path follow_symlinks(const std::filesystem::path& target) {
  constexpr int kMaxLinks = 40;  // Linux's own limit (ELOOP)
  std::filesystem::path path = target;
  for (int i = 0; i < kMaxLinks; ++i) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(path, ec)) return path;
    const std::filesystem::path link = std::filesystem::read_symlink(path, ec);
    if (ec) io::fail(target, ec.message());
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
  io::fail(target, "too many levels of symbolic links");
}

}  // namespace deformcd

namespace deformcd::io {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {}

AtomicFile::~AtomicFile() {
  if (file_) std::fclose(file_);  // frees an unnamed temporary
  if (!committed_ && !temporary_.empty()) {
    std::error_code ignored;  // nothing sensible to do if removal fails during unwinding
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::open() {
  if (target_ == "-") {
    kind_ = Kind::kStdout;
    open_direct();
    return;
  }
  // stat() follows the links as the kernel does, /proc/self/fd's too (/dev/stdout on a pipe
  // reads back as "pipe:[N]", not a path): a non-regular file is opened by the path as given.
  struct stat st {};
  const bool exists = ::stat(target_.c_str(), &st) == 0;
  if (exists && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode)) {
    kind_ = Kind::kDirect;
    replaced_ = target_;
    open_direct();
    return;
  }
  if (exists && S_ISREG(st.st_mode)) mode_ = static_cast<int>(st.st_mode & 07777);
  replaced_ = follow_symlinks(target_);
  open_temporary();
}

// Standard output or a device, FIFO or socket: there is nothing to replace, and replacing a
// device node (as root) or a FIFO would break what the user pointed us at.
void AtomicFile::open_direct() {
  const int fd = kind_ == Kind::kStdout
                     ? ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 0)
                     : ::open(replaced_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) fail(target_, std::strerror(errno));
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    fail(target_, std::strerror(error));
  }
}

void AtomicFile::open_temporary() {
  const std::filesystem::path dir =
      replaced_.has_parent_path() ? replaced_.parent_path() : std::filesystem::path(".");
  // O_TMPFILE: no name, so nothing to clean up if the process dies. Naming it at commit goes
  // through /proc/self/fd (linkat with AT_EMPTY_PATH would need CAP_DAC_READ_SEARCH).
  int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0 && ::access(proc_fd_path(fd).c_str(), F_OK) != 0) {
    ::close(fd);
    fd = -1;
  }
  if (fd < 0) {
    // A file system without O_TMPFILE (or a missing directory, reported below): a named
    // temporary. O_EXCL refuses to reuse a name that exists anyway.
    const std::filesystem::path temporary = temporary_name_for(replaced_);
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail(target_, std::strerror(errno));
    temporary_ = temporary;  // from here on the destructor removes it
  }
  file_ = ::fdopen(fd, "wb");
  if (!file_) {
    const int error = errno;
    ::close(fd);
    fail(target_, std::strerror(error));
  }
}

void AtomicFile::write(std::string_view contents) {
  if (committed_) fail(target_, "written after commit");
  if (!file_) open();
  if (std::fwrite(contents.data(), 1, contents.size(), file_) != contents.size()) {
    fail(target_, std::strerror(errno));
  }
}

std::string AtomicFile::path_for_child_process() {
  if (committed_) fail(target_, "written after commit");
  if (!file_) open();
  if (!temporary_.empty() && kind_ == Kind::kReplaced) return temporary_.string();
  // Our buffered bytes first, as the child writes through its own descriptor.
  if (std::fflush(file_) != 0) fail(target_, std::strerror(errno));
  const int fd = ::fileno(file_);
  const int flags = ::fcntl(fd, F_GETFD);
  if (flags < 0 || ::fcntl(fd, F_SETFD, flags & ~FD_CLOEXEC) != 0) {
    fail(target_, std::strerror(errno));
  }
  return proc_fd_path(fd);
}

void AtomicFile::commit() {
  if (!file_) fail(target_, "nothing was written");
  // A full disk may only show when the buffer is flushed.
  if (std::fflush(file_) != 0) fail(target_, std::strerror(errno));
  if (kind_ != Kind::kReplaced) {
    committed_ = true;
    if (std::fclose(std::exchange(file_, nullptr)) != 0) fail(target_, std::strerror(errno));
    return;
  }
  // The replacement keeps the permissions the user gave the file it replaces.
  if (mode_ >= 0 && ::fchmod(::fileno(file_), static_cast<mode_t>(mode_)) != 0) {
    fail(target_, std::strerror(errno));
  }
  if (temporary_.empty()) {
    const std::string proc = proc_fd_path(::fileno(file_));
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, replaced_.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      committed_ = true;
    } else if (errno == EEXIST) {
      const std::filesystem::path temporary = temporary_name_for(replaced_);
      if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, temporary.c_str(), AT_SYMLINK_FOLLOW) != 0) {
        fail(target_, std::strerror(errno));
      }
      temporary_ = temporary;
    } else {
      fail(target_, std::strerror(errno));
    }
  }
  std::FILE* file = std::exchange(file_, nullptr);
  if (std::fclose(file) != 0) fail(target_, std::strerror(errno));
  if (committed_) return;
  std::error_code ec;
  std::filesystem::rename(temporary_, replaced_, ec);
  if (ec) fail(target_, ec.message());
  committed_ = true;
}

void write_files_atomically(std::span<const FileContents> files) {
  std::vector<std::unique_ptr<AtomicFile>> written;
  written.reserve(files.size());
  for (const FileContents& file : files) {
    written.push_back(std::make_unique<AtomicFile>(file.target));
    written.back()->write(file.contents);
  }
  for (const FileContents& file : files) {
    std::error_code ec;
    if (std::filesystem::is_directory(file.target, ec)) fail(file.target, "it is a directory");
  }
  for (auto& file : written) {
    file->commit();
  }
}

}  // namespace deformcd::io

namespace deformcd {

struct StreamedFileWriter::File {
  explicit File(const std::filesystem::path& target) : file(target) {}
  io::AtomicFile file;
};

StreamedFileWriter::StreamedFileWriter(const std::filesystem::path& target)
    : file_(std::make_unique<File>(target)) {
  std::error_code ec;
  if (std::filesystem::is_directory(target, ec)) {
    throw Error("cannot write " + target.string() + ": it is a directory");
  }
  file_->file.write("");  // creates the temporary now: a bad directory fails before any work
}

StreamedFileWriter::~StreamedFileWriter() = default;

void StreamedFileWriter::append(std::string_view text) {
  file_->file.write(text);
}

void StreamedFileWriter::commit() {
  file_->file.commit();
}

std::string StreamedFileWriter::path_for_child_process() {
  return file_->file.path_for_child_process();
}

void write_file_atomically(const std::filesystem::path& file, std::string_view contents) {
  const io::FileContents one{file, std::string(contents)};
  io::write_files_atomically(std::span<const io::FileContents>(&one, 1));
}

}  // namespace deformcd
