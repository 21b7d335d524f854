#include "core/surface_extraction.h"

#include <algorithm>
#include <cstdint>
#include <sstream>

#include "deformcd/error.h"

namespace deformcd {

namespace {

// For a positively oriented tetrahedron (a, b, c, d), these local faces have outward normals.
constexpr int kOutwardFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};

struct FaceRef {
  Triangle key;        // sorted node indices
  std::uint32_t tet;   // owning tetrahedron
  std::uint8_t local;  // which of its four faces
  bool even;           // orientation parity relative to the sorted key
};

// True when the cyclic order (t0, t1, t2) is an even permutation of the sorted triple.
bool even_permutation(const Triangle& t) {
  const int inversions = (t[0] > t[1]) + (t[0] > t[2]) + (t[1] > t[2]);
  return inversions % 2 == 0;
}

}  // namespace

std::vector<Triangle> extract_boundary(const std::vector<Tetrahedron>& tets,
                                       const std::string& source) {
  std::vector<FaceRef> refs;
  refs.reserve(tets.size() * 4);
  for (std::uint32_t t = 0; t < tets.size(); ++t) {
    for (std::uint8_t f = 0; f < 4; ++f) {
      const Triangle tri{tets[t][kOutwardFaces[f][0]], tets[t][kOutwardFaces[f][1]],
                         tets[t][kOutwardFaces[f][2]]};
      Triangle key = tri;
      std::sort(key.begin(), key.end());
      refs.push_back({key, t, f, even_permutation(tri)});
    }
  }
  // Sorting by key groups the copies of a face; ties keep tetrahedron order (stable).
  std::stable_sort(refs.begin(), refs.end(),
                   [](const FaceRef& x, const FaceRef& y) { return x.key < y.key; });

  std::vector<std::uint8_t> is_boundary(tets.size() * 4, 0);
  for (std::size_t i = 0; i < refs.size();) {
    std::size_t j = i + 1;
    while (j < refs.size() && refs[j].key == refs[i].key)
      ++j;
    const std::size_t copies = j - i;
    if (copies == 1) {
      is_boundary[refs[i].tet * 4 + refs[i].local] = 1;
    } else if (copies > 2 || refs[i].even == refs[i + 1].even) {
      std::ostringstream msg;
      msg << "face (" << refs[i].key[0] << ' ' << refs[i].key[1] << ' ' << refs[i].key[2] << ") "
          << (copies > 2 ? "is shared by more than two tetrahedra"
                         : "has tetrahedra on the same side (overlapping elements)")
          << ": tetrahedra " << refs[i].tet << " and " << refs[i + 1].tet
          << " (0-based); the mesh is not a manifold solid";
      throw InputError(source, msg.str());
    }
    i = j;
  }

  std::vector<Triangle> boundary;
  for (std::uint32_t t = 0; t < tets.size(); ++t) {
    for (int f = 0; f < 4; ++f) {
      if (!is_boundary[t * 4 + f]) continue;
      boundary.push_back({tets[t][kOutwardFaces[f][0]], tets[t][kOutwardFaces[f][1]],
                          tets[t][kOutwardFaces[f][2]]});
    }
  }
  return boundary;
}

}  // namespace deformcd
