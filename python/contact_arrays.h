#pragma once
// Results out as NumPy arrays, one array per field, never one Python object per contact.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "deformcd/collision.h"

namespace deformcd::python {

namespace py = pybind11;

// {"body_a", "face_a", "body_b", "face_b"}: int64 (k,); {"nodes_a", "nodes_b"}: int64 (k, 3);
// "segment": float32 (k, 2, 3) (zeros for coplanar pairs); "coplanar": bool (k,). Row i of
// every array is contact i, in the detector's order.
py::dict contact_arrays(const std::vector<Contact>& contacts);

// {"contacts", "box_pairs", "colliding_faces", "candidates"}: ints.
py::dict counts_dict(const CollisionCounts& counts);

// flags[begin, begin + count) as a bool array.
py::array_t<bool> flag_array(const std::vector<std::uint32_t>& flags, std::size_t begin,
                             std::size_t count);

}  // namespace deformcd::python
