#pragma once
/// \file io.h
/// Reading and writing mesh files. Every reader validates what it returns (mesh_validation.h)
/// and throws InputError naming the file, the line and what is wrong.

#include <filesystem>
#include <memory>
#include <string_view>

#include "deformcd/mesh.h"

namespace deformcd {

/// Reads a TetGen mesh: PREFIX.node and PREFIX.ele, and PREFIX.face when it exists.
/// `prefix` may also name one of those files (its extension is dropped).
/// Accepts what TetGen writes and reads: '#' comments, blank lines, attributes and boundary
/// markers (checked to be numbers, then ignored), 0- or 1-based indices (taken from the first
/// node's index; every file's record indices must then be consecutive), 4-node tetrahedra.
/// Second-order (10-node) tetrahedra are rejected: their edge nodes would be free particles.
[[nodiscard]] TetMesh read_tetgen(const std::filesystem::path& prefix);

/// Writes PREFIX.node, PREFIX.ele and PREFIX.face (`mesh.faces`, each with boundary marker 1;
/// a .face with no faces when `mesh.faces` is empty), 0-based, with shortest round-trip
/// doubles, so read_tetgen gives back the same mesh. `prefix` may end in .node/.ele/.face.
/// Writes to temporary files and renames them only once all are written, so a failure leaves
/// no partial output. Throws Error when a file cannot be written or the mesh has a non-finite
/// coordinate or an index out of range.
void write_tetgen(const TetMesh& mesh, const std::filesystem::path& prefix);

/// True when `file`'s extension names a surface format read_surface knows (.off .obj .stl .ply,
/// any case).
[[nodiscard]] bool is_surface_file(const std::filesystem::path& file);

/// Reads a triangulated surface: OFF, OBJ (via tinyobjloader), STL (ASCII or binary) or PLY
/// (ASCII or binary, either endianness). Polygons are fan-triangulated. Vertices keep the file's
/// order; STL, which stores corners rather than shared vertices, has its exactly equal corners
/// welded in order of first appearance.
[[nodiscard]] SurfaceMesh read_surface(const std::filesystem::path& file);

/// Writes an OFF file of triangles, with shortest round-trip doubles (atomically, and with the
/// same checks, as write_tetgen).
void write_off(const SurfaceMesh& mesh, const std::filesystem::path& file);

/// Every writer below writes its path as follows: "-" is standard output; a device, FIFO or
/// socket is written directly, never replaced; a symbolic link is followed and its final target
/// replaced atomically (keeping the link); an existing regular file is replaced atomically and
/// its permission bits kept. Only replaced files have the all-or-nothing guarantee.
///
/// A file written piece by piece (e.g. one line per frame) under a temporary next to `target`,
/// which commit() gives the target's name. Destroyed without commit() (an error on the way),
/// or the process killed (SIGINT, SIGTERM, SIGKILL) before it, it leaves nothing behind, and an
/// existing target is untouched: the temporary is an unnamed file (O_TMPFILE) where the file
/// system allows it. Throws Error naming the target when the temporary cannot be created or
/// written.
class StreamedFileWriter {
 public:
  /// Creates the temporary beside `target` (throws Error naming the target).
  explicit StreamedFileWriter(const std::filesystem::path& target);
  ~StreamedFileWriter();
  StreamedFileWriter(const StreamedFileWriter&) = delete;
  StreamedFileWriter& operator=(const StreamedFileWriter&) = delete;
  /// Writes `text` at the end of the temporary.
  void append(std::string_view text);
  /// Flushes the temporary and gives it the target's name, replacing any file there.
  void commit();

  /// A path through which a child process (ffmpeg, gnuplot) can write the temporary itself,
  /// for outputs that another program produces: "/proc/self/fd/N", whose descriptor children
  /// spawned from now on inherit (so that /proc/self in the child names the same file), or the
  /// temporary's own name where it has one. The path has no extension: tell the program the
  /// format (ffmpeg -f mp4). The child opens and truncates the temporary; commit() names it.
  [[nodiscard]] std::string path_for_child_process();

 private:
  struct File;
  std::unique_ptr<File> file_;
};

/// `target` with its symbolic links followed (a link's relative target is read from the link's
/// directory): the file an output path writes. A dangling link gives the name it points to.
/// Throws Error naming `target` for a loop (over 40 links).
[[nodiscard]] std::filesystem::path follow_symlinks(const std::filesystem::path& target);

/// Writes `contents` to `file` through a temporary file renamed into place, so a failure leaves
/// neither a partial file nor a temporary. Throws Error naming the file.
void write_file_atomically(const std::filesystem::path& file, std::string_view contents);

}  // namespace deformcd
