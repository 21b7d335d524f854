// deformcd::tetrahedralize: check the surface, run TetGen isolated, validate what comes back.

#include <cmath>
#include <cstring>
#include <sstream>

#include "deformcd/error.h"
#include "deformcd/mesh_validation.h"
#include "deformcd/tetrahedralize.h"
#include "tetgen/isolated_run.h"
#include "tetgen/tetgen_run.h"

namespace deformcd {

namespace {

std::string switches_for(const TetrahedralizeOptions& options, const std::string& source) {
  // p: the input is a piecewise linear complex; z: number from zero; Q: quiet.
  std::ostringstream s;
  s.precision(17);
  s << "pzQ";
  if (options.preserve_surface) s << 'Y';
  if (options.quality) {
    if (!(*options.quality >= 1.0) || !std::isfinite(*options.quality)) {
      throw InputError(source, "quality (radius-edge ratio bound) must be >= 1, got " +
                                   std::to_string(*options.quality));
    }
    s << 'q' << *options.quality;
  }
  if (options.max_volume) {
    if (!(*options.max_volume > 0.0) || !std::isfinite(*options.max_volume)) {
      throw InputError(source,
                       "max volume must be positive, got " + std::to_string(*options.max_volume));
    }
    s << 'a' << *options.max_volume;
  }
  return s.str();
}

std::string log_excerpt(const std::string& log) {
  constexpr std::size_t kMax = 2000;
  if (log.empty()) return "";
  return "\nTetGen said:\n" + (log.size() > kMax ? log.substr(0, kMax) + "\n[...]" : log);
}

}  // namespace

TetMesh tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options,
                       const std::string& source) {
  validate_surface_mesh(surface, {source, {}, source, {}, 0});
  check_closed_surface(surface, source);
  const std::string switches = switches_for(options, source);

  // TetGen runs in a child process: it can crash on bad input, and that must not end ours.
  const detail::IsolatedResult run = detail::run_isolated(
      [&](std::string& output) { return detail::run_tetgen(surface, switches, output); });
  if (run.signal != 0) {
    throw InputError(source, "TetGen crashed (signal " + std::to_string(run.signal) + ", " +
                                 strsignal(run.signal) +
                                 ") on this surface; check it for self-intersections and "
                                 "near-coincident faces" +
                                 log_excerpt(run.log));
  }
  if (run.exit_status == detail::kSelfIntersecting) {
    throw InputError(source, "the surface intersects itself (" + run.output +
                                 " faces involved); TetGen needs a surface without "
                                 "self-intersections" +
                                 log_excerpt(run.log));
  }
  if (!run.ok) {
    const std::string message =
        "tetrahedralization failed: " + detail::explain_tetgen_failure(run.exit_status) +
        log_excerpt(run.log);
    if (run.exit_status == 1) throw Error(source + ": " + message);
    throw InputError(source, message);
  }

  TetMesh mesh = detail::deserialize_tetgen_output(run.output);
  if (mesh.tetrahedra.empty()) {
    throw InputError(source, "tetrahedralization produced no tetrahedra");
  }
  const std::string result_name = source + " (tetrahedralized)";
  validate_tet_mesh(mesh, {result_name, {}, result_name, {}, 0});
  return mesh;
}

}  // namespace deformcd
