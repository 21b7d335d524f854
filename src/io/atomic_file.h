#pragma once
// Writing files so that each appears whole or not at all, even when the process is killed
// (SIGINT, SIGTERM, SIGKILL) while writing: contents go to an unnamed temporary file
// (O_TMPFILE) in the target's directory, which the kernel frees if the process dies, and which
// is given the target's name only once everything was written. Where the file system has no
// O_TMPFILE (or /proc is not mounted) the temporary is a hidden named file next to the target,
// removed on errors but left behind if the process is killed.
//
// What a target path names decides how it is written (the one place that decides it, for every
// writer and every output option of the tool):
// - "-": standard output, written directly (nothing to replace);
// - an existing file that is not a regular file or a directory (a device such as /dev/null or
//   /dev/full, a FIFO, a socket): opened and written directly, never replaced;
// - a symbolic link: followed (links to links too); its final target is replaced atomically,
//   with the temporary in the target's directory, and the link is kept;
// - a regular file or a new name: replaced atomically; an existing file's permission bits are
//   given to its replacement.

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace deformcd::io {

/// One file written under a temporary and given its target's name by commit(). Destroyed
/// without a commit (an exception on the way), it leaves nothing; killed before the commit, it
/// leaves nothing either (unless it had to use a named temporary, see named_temporary()).
class AtomicFile {
 public:
  /// How the target is written (see the file's comment).
  enum class Kind {
    kReplaced,  ///< a regular file or a new name (a symlink's final target): atomic replacement
    kDirect,    ///< a device, FIFO or socket: written directly
    kStdout,    ///< "-": standard output
  };

  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends `contents` to the temporary (created by the first call).
  /// Throws Error naming the target when it cannot be created or written in full.
  void write(std::string_view contents);

  /// Flushes the temporary and gives it the target's name, replacing an existing target
  /// atomically. Throws Error naming the target.
  ///
  /// An unnamed temporary becomes the target with one link when there is no target yet. To
  /// replace a target it is linked under a hidden name and renamed onto it (a link cannot
  /// replace a file): a kill between those two calls leaves the hidden name behind.
  void commit();

  /// A path a child process can open to write the temporary (StreamedFileWriter's contract):
  /// "/proc/self/fd/N" with FD_CLOEXEC cleared, or the named temporary. Creates the temporary.
  [[nodiscard]] std::string path_for_child_process();

  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// The temporary's name when it has one: a file system without O_TMPFILE, or during commit().
  /// Empty while the temporary is unnamed (or before write()).
  [[nodiscard]] const std::filesystem::path& named_temporary() const { return temporary_; }
  /// True once write() has created the temporary.
  [[nodiscard]] bool is_open() const { return file_ != nullptr; }
  /// How the target is written; known once write() opened it.
  [[nodiscard]] Kind kind() const { return kind_; }

 private:
  void open();
  void open_direct();
  void open_temporary();

  std::filesystem::path target_;
  std::filesystem::path replaced_;  // the file replaced: the target, its symlinks followed
  Kind kind_ = Kind::kReplaced;
  int mode_ = -1;  // an existing target's permission bits, given to its replacement
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

/// What to write where.
struct FileContents {
  std::filesystem::path target;
  std::string contents;
};

/// Writes every file to its temporary first and names them all only after every write
/// succeeded, and after checking that no target is a directory, so that the usual failures
/// (missing directory, no permission, disk full, a directory in the way) leave no file,
/// temporary or final. A commit failing after others succeeded, or the process being killed
/// between two commits, could still leave some targets replaced and not others.
void write_files_atomically(std::span<const FileContents> files);

}  // namespace deformcd::io
