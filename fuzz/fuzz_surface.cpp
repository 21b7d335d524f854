// Fuzz target of one surface reader (OFF, OBJ, STL or PLY, as DEFORMCD_FUZZ_FORMAT says): the
// input is a whole file. A mesh that reads must also survive the round trip through OFF text
// (write_off's writer, then the OFF reader) bit for bit.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "io/surface_formats.h"

namespace {

using deformcd::SurfaceMesh;
using deformcd::io::SurfaceFormat;

constexpr SurfaceFormat kFormat = SurfaceFormat::DEFORMCD_FUZZ_FORMAT;
constexpr const char* kFile = DEFORMCD_FUZZ_NAME;

void check_round_trip(const SurfaceMesh& mesh) {
  const std::string text = deformcd::io::off_text(mesh);
  SurfaceMesh again;
  const bool read = deformcd::fuzz::reads_or_rejects(
      [&] { again = deformcd::io::parse_surface(text, SurfaceFormat::kOff, "again.off"); },
      "again.off");
  if (!read) deformcd::fuzz::finding("a mesh that read does not read back from its OFF text");
  if (again.vertices != mesh.vertices || again.triangles != mesh.triangles) {
    deformcd::fuzz::finding("the OFF round trip changed the mesh");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  SurfaceMesh mesh;
  if (deformcd::fuzz::reads_or_rejects(
          [&] { mesh = deformcd::io::parse_surface(input, kFormat, kFile); }, kFile)) {
    check_round_trip(mesh);
  }
  return 0;
}
