// Checks, before TetGen sees a surface, that it bounds a solid. TetGen's own reaction to an
// open surface is an obscure failure (or a mesh of the convex hull), so we name the first open
// or inconsistently oriented edge instead.

#include <algorithm>
#include <cstdint>
#include <map>
#include <sstream>

#include "deformcd/error.h"
#include "deformcd/tetrahedralize.h"

namespace deformcd {

namespace {

struct EdgeUse {
  std::uint32_t forward = 0;   // uses as (min, max)
  std::uint32_t backward = 0;  // uses as (max, min)
  std::uint32_t first_triangle = 0;
};

std::string edge_name(std::uint32_t a, std::uint32_t b) {
  std::ostringstream s;
  s << "edge (" << a << ' ' << b << ")";
  return s.str();
}

}  // namespace

void check_closed_surface(const SurfaceMesh& surface, const std::string& source) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, EdgeUse> edges;
  std::map<Triangle, std::uint32_t> seen;
  for (std::uint32_t t = 0; t < surface.triangles.size(); ++t) {
    const Triangle& tri = surface.triangles[t];
    Triangle key = tri;
    std::sort(key.begin(), key.end());
    if (auto [it, inserted] = seen.emplace(key, t); !inserted) {
      std::ostringstream msg;
      msg << "triangle " << t << " repeats triangle " << it->second
          << " (0-based); the surface must bound a solid";
      throw InputError(source, msg.str());
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      EdgeUse& use = edges[{std::min(a, b), std::max(a, b)}];
      if (use.forward + use.backward == 0) use.first_triangle = t;
      (a < b ? use.forward : use.backward) += 1;
    }
  }
  std::size_t open = 0, nonmanifold = 0, flipped = 0;
  std::string first;
  for (const auto& [edge, use] : edges) {
    const std::uint32_t total = use.forward + use.backward;
    const char* problem = nullptr;
    if (total == 1) {
      problem = "is a boundary edge (the surface has a hole)";
      ++open;
    } else if (total > 2) {
      problem = "is shared by more than two triangles (non-manifold)";
      ++nonmanifold;
    } else if (use.forward != 1) {
      problem = "is used twice in the same direction (inconsistent orientation)";
      ++flipped;
    }
    if (problem && first.empty()) {
      std::ostringstream msg;
      msg << edge_name(edge.first, edge.second) << " of triangle " << use.first_triangle << ' '
          << problem;
      first = msg.str();
    }
  }
  if (!first.empty()) {
    std::ostringstream msg;
    msg << "surface is not closed and consistently oriented: " << open << " boundary edge(s), "
        << nonmanifold << " non-manifold edge(s), " << flipped
        << " inconsistently oriented edge(s); first: " << first
        << " (0-based vertex indices). Close holes and fix orientation before tetrahedralizing";
    throw InputError(source, msg.str());
  }
}

}  // namespace deformcd
