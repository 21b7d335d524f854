#pragma once
// The three files of a TetGen mesh, named from a prefix or from one of the files.

#include <filesystem>

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

}  // namespace deformcd::io
