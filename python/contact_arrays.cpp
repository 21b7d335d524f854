#include "contact_arrays.h"

namespace deformcd::python {

namespace {

py::array_t<std::int64_t> int_array(std::size_t rows, std::size_t columns = 0) {
  const auto k = static_cast<py::ssize_t>(rows);
  if (columns == 0) return py::array_t<std::int64_t>(k);
  return py::array_t<std::int64_t>({k, static_cast<py::ssize_t>(columns)});
}

}  // namespace

py::dict contact_arrays(const std::vector<Contact>& contacts) {
  const std::size_t k = contacts.size();
  auto body_a = int_array(k), face_a = int_array(k), body_b = int_array(k), face_b = int_array(k);
  auto nodes_a = int_array(k, 3), nodes_b = int_array(k, 3);
  py::array_t<float> segment({static_cast<py::ssize_t>(k), py::ssize_t{2}, py::ssize_t{3}});
  py::array_t<bool> coplanar(static_cast<py::ssize_t>(k));
  std::int64_t* ba = body_a.mutable_data();
  std::int64_t* fa = face_a.mutable_data();
  std::int64_t* bb = body_b.mutable_data();
  std::int64_t* fb = face_b.mutable_data();
  std::int64_t* na = nodes_a.mutable_data();
  std::int64_t* nb = nodes_b.mutable_data();
  float* s = segment.mutable_data();
  bool* cp = coplanar.mutable_data();
  for (std::size_t i = 0; i < k; ++i) {
    const Contact& c = contacts[i];
    ba[i] = c.a.body;
    fa[i] = c.a.face;
    bb[i] = c.b.body;
    fb[i] = c.b.face;
    for (std::size_t j = 0; j < 3; ++j) {
      na[3 * i + j] = c.a.nodes[j];
      nb[3 * i + j] = c.b.nodes[j];
      s[6 * i + j] = c.segment[0][static_cast<glm::length_t>(j)];
      s[6 * i + 3 + j] = c.segment[1][static_cast<glm::length_t>(j)];
    }
    cp[i] = c.coplanar;
  }
  py::dict d;
  d["body_a"] = body_a;
  d["face_a"] = face_a;
  d["body_b"] = body_b;
  d["face_b"] = face_b;
  d["nodes_a"] = nodes_a;
  d["nodes_b"] = nodes_b;
  d["segment"] = segment;
  d["coplanar"] = coplanar;
  return d;
}

py::dict counts_dict(const CollisionCounts& counts) {
  py::dict d;
  d["contacts"] = counts.contacts;
  d["box_pairs"] = counts.box_pairs;
  d["colliding_faces"] = counts.colliding_faces;
  d["candidates"] = counts.candidates;
  return d;
}

py::array_t<bool> flag_array(const std::vector<std::uint32_t>& flags, std::size_t begin,
                             std::size_t count) {
  py::array_t<bool> out(static_cast<py::ssize_t>(count));
  bool* p = out.mutable_data();
  for (std::size_t i = 0; i < count; ++i)
    p[i] = flags[begin + i] != 0;
  return out;
}

}  // namespace deformcd::python
