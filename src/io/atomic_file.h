#pragma once
// Writing files so that a failure leaves nothing behind: contents go to a temporary file in the
// target's directory (so the final rename stays within one file system and is atomic), and are
// renamed into place only once everything was written.

#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace deformcd::io {

/// One file written under a temporary name and renamed onto its target by commit(). Destroyed
/// without a commit (an exception on the way), it removes the temporary file.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  /// Appends `contents` to the temporary file next to the target (created by the first call).
  /// Throws Error naming the target when the file cannot be created or written in full.
  void write(std::string_view contents);

  /// Closes the temporary file and renames it onto the target. Throws Error naming the target.
  void commit();

  [[nodiscard]] const std::filesystem::path& target() const { return target_; }
  /// The temporary file's path (empty before write()).
  [[nodiscard]] const std::filesystem::path& temporary() const { return temporary_; }

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::FILE* file_ = nullptr;
  bool committed_ = false;
};

/// What to write where.
struct FileContents {
  std::filesystem::path target;
  std::string contents;
};

/// Writes every file to its temporary first and renames them all only after every write
/// succeeded, and after checking that no target is a directory, so that the usual failures
/// (missing directory, no permission, disk full, a directory in the way) leave no file,
/// temporary or final. A rename failing after others succeeded could still leave some targets
/// replaced; within one directory that would take a concurrent change to the directory.
void write_files_atomically(std::span<const FileContents> files);

}  // namespace deformcd::io
