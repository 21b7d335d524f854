#include "array_conversion.h"

#include <cstring>
#include <limits>

#include "deformcd/error.h"

namespace deformcd::python {

namespace {

std::string dtype_name(const py::array& array) {
  return py::str(array.dtype()).cast<std::string>();
}

// The caller's array itself, when the detector can read it where it is.
std::optional<HostPositions> in_place_layout(const py::array& array) {
  if (!py::isinstance<py::array_t<float>>(array)) return std::nullopt;  // dtype, byte order
  const py::ssize_t rows = array.shape(0);
  const py::ssize_t row_stride = array.strides(0);
  const auto address = reinterpret_cast<std::uintptr_t>(array.data());
  if (rows == 0 || array.strides(1) != py::ssize_t{sizeof(float)} ||
      address % alignof(float) != 0) {
    return std::nullopt;
  }
  if (rows == 1) return HostPositions{static_cast<const float*>(array.data()), 3 * sizeof(float)};
  if (row_stride < py::ssize_t{3 * sizeof(float)} || row_stride % py::ssize_t{sizeof(float)} != 0) {
    return std::nullopt;
  }
  return HostPositions{static_cast<const float*>(array.data()),
                       static_cast<std::size_t>(row_stride)};
}

}  // namespace

std::string shape_string(const py::array& array) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    if (i > 0) s += ", ";
    s += std::to_string(array.shape(i));
  }
  return s + (array.ndim() == 1 ? ",)" : ")");
}

HeldPositions hold_positions(const py::handle& object, const std::string& what,
                             std::optional<std::uint32_t> vertex_count, const std::string& whose) {
  const py::array array = py::array::ensure(object);
  if (!array) {
    throw py::value_error(what + " must be an array of shape (n, 3), got a " +
                          py::str(py::type::of(object).attr("__name__")).cast<std::string>());
  }
  if (array.dtype().kind() != 'f' || (array.itemsize() != 4 && array.itemsize() != 8)) {
    throw py::value_error(what + " must be float32 or float64, got " + dtype_name(array));
  }
  const bool rows_ok = array.ndim() == 2 && array.shape(1) == 3;
  if (!rows_ok || (vertex_count && array.shape(0) != py::ssize_t{*vertex_count})) {
    std::string expected = "(n, 3)";
    if (vertex_count) {
      expected += " with n = " + std::to_string(*vertex_count) + " vertices";
      if (!whose.empty()) expected += " of " + whose;
    }
    throw py::value_error(what + " must have shape " + expected + ", got " + shape_string(array));
  }
  if (const std::optional<HostPositions> host = in_place_layout(array)) {
    return {array, *host, true};
  }
  // One conversion (dtype, byte order, strides, alignment at once) into an array of ours.
  py::array copy = py::module_::import("numpy").attr("require")(
      array, "float32", py::make_tuple("C_CONTIGUOUS", "ALIGNED", "OWNDATA"));
  return {copy, HostPositions{static_cast<const float*>(copy.data()), 3 * sizeof(float)}, false};
}

std::vector<Triangle> triangles_from_array(const py::handle& object, const std::string& what,
                                           const std::string& mesh_label,
                                           std::uint32_t vertex_count) {
  const py::array array = py::array::ensure(object);
  if (!array) throw py::value_error(what + " must be an integer array of shape (m, 3)");
  if (array.dtype().kind() != 'i' && array.dtype().kind() != 'u') {
    throw py::value_error(what + " must be an integer array, got " + dtype_name(array));
  }
  if (array.ndim() != 2 || array.shape(1) != 3) {
    throw py::value_error(what + " must have shape (m, 3), got " + shape_string(array));
  }
  // Values past int64 (uint64 only) come out negative here, and are reported as out of range.
  // The converting constructor keeps numpy's own error (MemoryError for an array too large to
  // convert); ensure() would clear it and leave nothing to raise.
  const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> indices(array);
  const std::int64_t* p = indices.data();
  std::vector<Triangle> triangles(static_cast<std::size_t>(array.shape(0)));
  for (std::size_t t = 0; t < triangles.size(); ++t, p += 3) {
    for (int k = 0; k < 3; ++k) {
      if (p[k] < 0 || p[k] > std::int64_t{std::numeric_limits<std::uint32_t>::max()}) {
        throw InputError(mesh_label, "triangle " + std::to_string(t) + " (" + std::to_string(p[0]) +
                                         ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) +
                                         ") has vertex index " + std::to_string(p[k]) +
                                         ", out of range (the mesh has " +
                                         std::to_string(vertex_count) + " vertices)");
      }
      triangles[t][static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(p[k]);
    }
  }
  return triangles;
}

py::array_t<float> vec3_array(const std::vector<glm::vec3>& v) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  py::array_t<float> out({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  if (!v.empty()) std::memcpy(out.mutable_data(), &v[0].x, v.size() * sizeof(glm::vec3));
  return out;
}

py::array_t<std::int64_t> triangle_array(const std::vector<Triangle>& triangles) {
  py::array_t<std::int64_t> out({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
  std::int64_t* p = out.mutable_data();
  for (const Triangle& t : triangles) {
    for (std::uint32_t v : t)
      *p++ = v;
  }
  return out;
}

}  // namespace deformcd::python
