#pragma once
// The boundary surface of a tetrahedral mesh.

#include <string>
#include <vector>

#include "deformcd/mesh.h"

namespace deformcd {

/// The faces that belong to exactly one tetrahedron, oriented outward (counter-clockwise seen
/// from outside), in the order of their tetrahedra. Tetrahedra must be positively oriented.
/// Throws InputError (naming `source`) when a face is shared by more than two tetrahedra or two
/// tetrahedra on one face are on the same side of it (overlapping elements).
[[nodiscard]] std::vector<Triangle> extract_boundary(const std::vector<Tetrahedron>& tets,
                                                     const std::string& source);

}  // namespace deformcd
