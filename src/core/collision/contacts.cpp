#include "core/collision/contacts.h"

#include <algorithm>
#include <tuple>

namespace deformcd::collision {

namespace {

ContactFace contact_face(std::uint32_t global_face, const std::vector<gpu::Face>& faces,
                         const std::vector<gpu::MeshInfo>& meshes) {
  const gpu::Face& f = faces.at(global_face);
  return {f.body, global_face - meshes.at(f.body).face_offset, {f.a, f.b, f.c}};
}

}  // namespace

std::vector<Contact> make_contacts(const std::vector<gpu::FacePair>& pairs,
                                   const std::vector<gpu::Face>& faces,
                                   const std::vector<gpu::MeshInfo>& meshes) {
  std::vector<Contact> contacts;
  contacts.reserve(pairs.size());
  for (const gpu::FacePair& p : pairs) {
    Contact c;
    c.a = contact_face(p.face_a, faces, meshes);
    c.b = contact_face(p.face_b, faces, meshes);
    c.coplanar = p.coplanar != 0u;
    c.segment = {glm::vec3(p.segment0), glm::vec3(p.segment1)};
    if (c.b.body < c.a.body) std::swap(c.a, c.b);
    contacts.push_back(c);
  }
  std::sort(contacts.begin(), contacts.end(), [](const Contact& x, const Contact& y) {
    return std::tie(x.a.body, x.a.face, x.b.body, x.b.face) <
           std::tie(y.a.body, y.a.face, y.b.body, y.b.face);
  });
  return contacts;
}

}  // namespace deformcd::collision
