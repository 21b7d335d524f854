#include "core/collision/proximity.h"

#include <algorithm>
#include <map>
#include <utility>

namespace deformcd::collision {

std::vector<std::uint32_t> primitive_owners(const std::vector<gpu::Face>& faces) {
  std::vector<std::uint32_t> owners(faces.size(), 0u);
  // Faces are laid out mesh by mesh: walk each mesh's run with its own maps, in face order, so
  // the first face to name a vertex or an edge owns it.
  std::size_t begin = 0;
  while (begin < faces.size()) {
    std::size_t end = begin;
    while (end < faces.size() && faces[end].body == faces[begin].body)
      ++end;
    std::map<std::uint32_t, std::size_t> vertex_owner;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> edge_owner;
    for (std::size_t f = begin; f < end; ++f) {
      for (std::uint32_t k = 0; k < 3u; ++k) {
        const std::uint32_t v = face_corner(faces[f], k);
        const std::uint32_t w = face_corner(faces[f], kNextCorner[k]);
        if (vertex_owner.emplace(v, f).second) owners[f] |= kOwnsVertex0 << k;
        if (edge_owner.emplace(std::minmax(v, w), f).second) owners[f] |= kOwnsEdge0 << k;
      }
    }
    begin = end;
  }
  return owners;
}

}  // namespace deformcd::collision
