#pragma once
// From the backends' raw face pairs (face indices over every mesh) to the contacts users see
// (mesh and triangle indices in the caller's order), in one order that does not depend on the
// backend.

#include <vector>

#include "deformcd/collision.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Contacts sorted by (mesh a, face a, mesh b, face b). `faces` (mesh-local vertex indices) and
/// `meshes` are the detector's.
[[nodiscard]] std::vector<Contact> make_contacts(const std::vector<gpu::FacePair>& pairs,
                                                 const std::vector<gpu::Face>& faces,
                                                 const std::vector<gpu::MeshInfo>& meshes);

}  // namespace deformcd::collision
