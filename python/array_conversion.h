#pragma once
// NumPy arrays in: vertex positions (read in place when they already have the detector's layout,
// else converted once into a float32 array the binding owns) and triangle indices; and
// (n, 3) float32 arrays out.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <glm/vec3.hpp>

#include "deformcd/detector.h"
#include "deformcd/mesh.h"

namespace deformcd::python {

namespace py = pybind11;

// Positions as the detector reads them, and the array that holds them: the caller's own array
// when it is float32 in native byte order, aligned, with xyz packed in each row (any row stride
// that is a positive multiple of 4 bytes, at least 12: C-contiguous (n, 3), or the first three
// columns of an (n, 4)), so that changing it in place moves the mesh; otherwise one float32
// C-contiguous copy made here. Whoever keeps `host` must keep `array` alive.
struct HeldPositions {
  py::array array;
  HostPositions host;
  bool in_place = false;  // `array` is the caller's object
};

// Raises ValueError naming `what` (e.g. "set_positions: positions") for an object that is not a
// float32 / float64 array of shape (n, 3); with `vertex_count`, n must equal it, and `whose`
// (e.g. "mesh 1") names the mesh in the message.
HeldPositions hold_positions(const py::handle& object, const std::string& what,
                             std::optional<std::uint32_t> vertex_count = std::nullopt,
                             const std::string& whose = {});

// Triangles from an integer array of shape (m, 3). ValueError for another dtype or shape,
// InputError worded as the detector's, naming `mesh_label` and the triangle, for a negative
// index or one past 2^32 - 1, which the detector's uint32 indices cannot carry (indices past
// `vertex_count` are left to the detector, which says the same).
std::vector<Triangle> triangles_from_array(const py::handle& object, const std::string& what,
                                           const std::string& mesh_label,
                                           std::uint32_t vertex_count);

// A (n, 3) float32 array holding a copy of `v`.
py::array_t<float> vec3_array(const std::vector<glm::vec3>& v);

// A (n, 3) array of `triangles` (int64).
py::array_t<std::int64_t> triangle_array(const std::vector<Triangle>& triangles);

// "(640, 3)": a shape for messages.
std::string shape_string(const py::array& array);

}  // namespace deformcd::python
