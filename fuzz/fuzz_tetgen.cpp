// Fuzz target of the TetGen reader. The input holds the three files separated by NUL bytes:
// NODE \0 ELE [\0 FACE] (no FACE part: no .face file, as when it does not exist), so that
// mutations can make the files disagree with each other. A mesh that reads must also survive
// the round trip through write_tetgen's writer bit for bit.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "fuzz_support.h"
#include "io/tetgen_files.h"

namespace {

using deformcd::TetMesh;
using deformcd::io::TetGenText;

void check_round_trip(const TetMesh& mesh) {
  const deformcd::io::TetGenFileTexts texts =
      deformcd::io::tetgen_texts(mesh, deformcd::io::tetgen_files("again"));
  TetMesh again;
  const bool read = deformcd::fuzz::reads_or_rejects(
      [&] {
        again = deformcd::io::parse_tetgen({"again.node", texts.node}, {"again.ele", texts.ele},
                                           TetGenText{"again.face", texts.face});
      },
      "again.");
  if (!read) deformcd::fuzz::finding("a mesh that read does not read back from its own files");
  if (again.nodes != mesh.nodes || again.tetrahedra != mesh.tetrahedra ||
      again.faces != mesh.faces) {
    deformcd::fuzz::finding("the TetGen round trip changed the mesh");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string_view parts[3];
  std::size_t count = 0;
  for (; count < 3; ++count) {
    const std::size_t nul = input.find('\0');
    parts[count] = input.substr(0, nul);
    if (nul == std::string_view::npos) {
      ++count;
      break;
    }
    input.remove_prefix(nul + 1);
  }
  if (count < 2) return 0;  // not even a .node and an .ele: nothing the reader would be given

  std::optional<TetGenText> face;
  if (count == 3) face = TetGenText{"fuzz.face", parts[2]};
  TetMesh mesh;
  if (deformcd::fuzz::reads_or_rejects(
          [&] {
            mesh =
                deformcd::io::parse_tetgen({"fuzz.node", parts[0]}, {"fuzz.ele", parts[1]}, face);
          },
          "fuzz.")) {
    check_round_trip(mesh);
  }
  return 0;
}
