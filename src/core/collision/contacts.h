#pragma once
// From the backends' raw face pairs (global face indices) to the contacts users see (body and
// face indices within the body), in one order that does not depend on the backend.

#include <vector>

#include "deformcd/collision.h"
#include "deformcd/gpu_layout.h"

namespace deformcd::collision {

/// Contacts sorted by (body a, face a, body b, face b). `faces` and `objects` are the world's.
[[nodiscard]] std::vector<Contact> make_contacts(const std::vector<gpu::FacePair>& pairs,
                                                 const std::vector<gpu::Face>& faces,
                                                 const std::vector<gpu::ObjectInfo>& objects);

}  // namespace deformcd::collision
