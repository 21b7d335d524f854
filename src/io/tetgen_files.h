#pragma once
// The three files of a TetGen mesh, named from a prefix or from one of the files, and reading
// them from memory.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "deformcd/mesh.h"

namespace deformcd::io {

struct TetGenFiles {
  std::filesystem::path node, ele, face;
};

/// PREFIX.node, PREFIX.ele and PREFIX.face. `prefix_or_file` may end in one of those extensions,
/// which is then dropped; any other extension is part of the prefix (TetGen's "bunny.1").
inline TetGenFiles tetgen_files(const std::filesystem::path& prefix_or_file) {
  std::filesystem::path prefix = prefix_or_file;
  const auto ext = prefix.extension();
  if (ext == ".node" || ext == ".ele" || ext == ".face") prefix.replace_extension();
  auto with = [&prefix](const char* extension) {
    std::filesystem::path p = prefix;
    p += extension;
    return p;
  };
  return {with(".node"), with(".ele"), with(".face")};
}

/// The contents write_tetgen writes.
struct TetGenFileTexts {
  std::string node, ele, face;
};

/// write_tetgen's contents for `mesh` (each file's first line, a comment, names its file).
/// Throws Error as write_tetgen does.
[[nodiscard]] TetGenFileTexts tetgen_texts(const TetMesh& mesh, const TetGenFiles& files);

/// One file's contents, and its name for messages.
struct TetGenText {
  std::string name;
  std::string_view text;
};

/// read_tetgen on contents already in memory (the fuzz target's entry point): parses the .node,
/// the .ele and, if given, the .face, checks them against each other and validates the mesh.
[[nodiscard]] TetMesh parse_tetgen(const TetGenText& node, const TetGenText& ele,
                                   const std::optional<TetGenText>& face);

}  // namespace deformcd::io
