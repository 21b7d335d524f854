// deformcd.Detector: deformcd::Detector over meshes given as NumPy arrays, whose positions are
// read in place from the caller's arrays (or from one float32 copy of them, see
// array_conversion.h); the arrays read are held here for as long as the detector reads them.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional arguments

#include "array_conversion.h"
#include "bindings.h"
#include "contact_arrays.h"
#include "deformcd/detector.h"
#include "deformcd/error.h"
#include "object_lock.h"

namespace deformcd::python {

namespace {

// As the detector names meshes in its messages.
std::string mesh_label(std::size_t mesh, const std::string& name) {
  std::string label = "mesh " + std::to_string(mesh);
  if (!name.empty()) label += " ('" + name + "')";
  return label;
}

struct MeshInput {
  CollisionMesh mesh;
  HeldPositions positions;
};

// meshes[m]: (vertices, faces), or a dict {"vertices", "faces", "self_collision", "name"}.
MeshInput mesh_from_python(const py::handle& item, std::size_t m) {
  const std::string where = "meshes[" + std::to_string(m) + "]";
  py::object vertices, faces;
  bool self_collision = false;
  std::string name;
  if (py::isinstance<py::dict>(item)) {
    const py::dict d = py::reinterpret_borrow<py::dict>(item);
    for (const auto& [key, value] : d) {
      const std::string k = py::str(key).cast<std::string>();
      if (k == "vertices") {
        vertices = py::reinterpret_borrow<py::object>(value);
      } else if (k == "faces") {
        faces = py::reinterpret_borrow<py::object>(value);
      } else if (k == "self_collision") {
        self_collision = value.cast<bool>();
      } else if (k == "name") {
        name = value.cast<std::string>();
      } else {
        std::string message = where;
        message += ": unknown key '" + k + "' (valid keys: vertices, faces, self_collision, name)";
        throw py::value_error(message);
      }
    }
    if (!vertices || !faces) throw py::value_error(where + " needs 'vertices' and 'faces'");
  } else if (py::isinstance<py::sequence>(item) && !py::isinstance<py::str>(item) &&
             py::len(item) == 2 && !py::isinstance<py::array>(item)) {
    const py::sequence pair = py::reinterpret_borrow<py::sequence>(item);
    vertices = pair[0];
    faces = pair[1];
  } else {
    throw py::value_error(where +
                          " must be a (vertices, faces) pair or a dict with 'vertices' and "
                          "'faces' (and optionally 'self_collision', 'name')");
  }
  MeshInput in;
  in.positions = hold_positions(vertices, where + " vertices");
  const py::ssize_t n = in.positions.array.shape(0);
  if (n > py::ssize_t{UINT32_MAX}) throw py::value_error(where + ": more than 2^32 - 1 vertices");
  in.mesh.vertex_count = static_cast<std::uint32_t>(n);
  in.mesh.triangles =
      triangles_from_array(faces, where + " faces", mesh_label(m, name), in.mesh.vertex_count);
  in.mesh.self_collision = self_collision;
  in.mesh.name = std::move(name);
  return in;
}

std::vector<MeshPair> mesh_pairs_from_python(const py::sequence& pairs) {
  std::vector<MeshPair> out;
  for (std::size_t i = 0; i < py::len(pairs); ++i) {
    const std::string where = "mesh_pairs[" + std::to_string(i) + "]";
    const py::object p = pairs[i];
    if (!py::isinstance<py::sequence>(p) || py::len(p) != 2) {
      throw py::value_error(where + " must be a pair of mesh indices (a, b)");
    }
    const auto a = p[py::int_(0)].cast<std::int64_t>();
    const auto b = p[py::int_(1)].cast<std::int64_t>();
    if (a < 0 || b < 0 || a > std::int64_t{UINT32_MAX} || b > std::int64_t{UINT32_MAX}) {
      throw py::value_error(where + " = (" + std::to_string(a) + ", " + std::to_string(b) +
                            "): mesh indices must be in [0, 2^32)");
    }
    out.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b)});
  }
  return out;
}

class PyDetector {
 public:
  PyDetector(const py::sequence& meshes, const std::string& backend, const std::string& broadphase,
             int threads, const py::object& mesh_pairs) {
    std::vector<CollisionMesh> collision_meshes;
    std::vector<HeldPositions> positions;
    for (std::size_t m = 0; m < py::len(meshes); ++m) {
      MeshInput in = mesh_from_python(meshes[m], m);
      collision_meshes.push_back(std::move(in.mesh));
      positions.push_back(std::move(in.positions));
    }
    DetectorOptions options;
    options.backend = parse_backend(backend);
    options.broadphase = parse_broadphase(broadphase);
    options.threads = threads;
    if (!mesh_pairs.is_none()) {
      if (!py::isinstance<py::sequence>(mesh_pairs)) {
        throw py::value_error("mesh_pairs must be None or a sequence of (a, b) mesh index pairs");
      }
      options.mesh_pairs = mesh_pairs_from_python(py::reinterpret_borrow<py::sequence>(mesh_pairs));
    }
    detector_ = std::make_unique<Detector>(std::move(collision_meshes), options);
    for (std::size_t m = 0; m < positions.size(); ++m) {
      detector_->set_positions(m, positions[m].host);
      held_.push_back(std::move(positions[m].array));
    }
  }

  void set_positions(std::int64_t mesh, const py::object& object) {
    const std::size_t m = existing_mesh(mesh, "set_positions", true);
    const CollisionMesh& info = detector_->mesh(m);  // meshes never change: no lock needed
    HeldPositions next = hold_positions(object, "set_positions: positions", info.vertex_count,
                                        mesh_label(m, info.name));
    const std::unique_lock<std::mutex> lock = lock_object(mutex_);
    detector_->set_positions(m, next.host);
    held_[m] = std::move(next.array);  // the old array is released only now
  }

  py::array positions(std::int64_t mesh) const { return held_[existing_mesh(mesh, "positions")]; }

  void detect() {
    without_gil(mutex_, [&] { detector_->detect(); });
  }
  void prepare() {
    without_gil(mutex_, [&] { detector_->prepare(); });
  }
  py::dict contacts() {
    return contact_arrays(without_gil(mutex_, [&] { return detector_->contacts(); }));
  }
  py::dict counts() {
    return counts_dict(without_gil(mutex_, [&] { return detector_->counts(); }));
  }
  py::array_t<bool> face_flags(const std::optional<std::int64_t>& mesh) {
    const std::optional<std::size_t> m =
        mesh ? std::optional<std::size_t>(existing_mesh(*mesh, "face_flags")) : std::nullopt;
    const std::vector<std::uint32_t> flags =
        without_gil(mutex_, [&] { return detector_->face_flags(); });
    if (!m) return flag_array(flags, 0, flags.size());
    return flag_array(flags, detector_->face_offset(*m), detector_->mesh(*m).triangles.size());
  }

  std::string broadphase() const { return std::string(broadphase_name(detector_->broadphase())); }
  void set_broadphase(const std::string& name) {
    const BroadPhase method = parse_broadphase(name);
    const std::unique_lock<std::mutex> lock = lock_object(mutex_);
    detector_->set_broadphase(method);
  }

  std::size_t mesh_count() const { return detector_->mesh_count(); }
  std::size_t face_count() const { return detector_->face_count(); }
  std::uint32_t vertex_count(std::int64_t mesh) const {
    return detector_->mesh(existing_mesh(mesh, "vertex_count")).vertex_count;
  }
  py::array_t<std::int64_t> faces(std::int64_t mesh) const {
    return triangle_array(detector_->mesh(existing_mesh(mesh, "faces")).triangles);
  }
  std::uint32_t face_offset(std::int64_t mesh) const {
    return detector_->face_offset(existing_mesh(mesh, "face_offset"));
  }
  std::string backend() const { return std::string(detector_->backend_name()); }
  std::string device() const { return detector_->device(); }
  std::string notice() const { return detector_->notice(); }

  std::string repr() const {
    return "<deformcd.Detector: " + std::to_string(mesh_count()) + " meshes, " +
           std::to_string(face_count()) + " triangles, backend " + backend() + ", broadphase " +
           broadphase() + ">";
  }

 private:
  // set_positions says what the C++ detector says (InputError); the getters raise IndexError.
  std::size_t existing_mesh(std::int64_t mesh, const char* call, bool input_error = false) const {
    const std::size_t count = detector_->mesh_count();
    if (mesh >= 0 && static_cast<std::size_t>(mesh) < count) return static_cast<std::size_t>(mesh);
    const std::string message = "mesh " + std::to_string(mesh) + " does not exist (there are " +
                                std::to_string(count) + " meshes)";
    if (input_error) throw InputError(call, message);
    throw py::index_error(std::string(call) + ": " + message);
  }

  std::unique_ptr<Detector> detector_;
  std::vector<py::array> held_;  // per mesh, the array detect() reads
  mutable std::mutex mutex_;
};

constexpr const char* kDetectorDoc =
    R"doc(Collision detection for triangle meshes given as NumPy arrays.

Detector(meshes, backend="auto", broadphase="bvh", threads=0, mesh_pairs=None)

Finds the intersecting triangle pairs between meshes (and within a mesh, with self-collision)
on the CPU (multithreaded) or on the GPU (OpenGL 4.3 compute shaders); every backend and
broad phase finds the same contacts, in the same order.

    import deformcd, numpy as np
    d = deformcd.Detector([(V0, F0), (V1, F1)], backend="cpu", broadphase="bvh")
    d.set_positions(1, V1_moved)   # (n, 3) float32 or float64
    d.detect()
    c = d.contacts()               # dict of arrays, one row per intersecting pair

Parameters
----------
meshes : sequence
    One item per mesh: a pair ``(vertices, faces)``, or a dict with the keys ``"vertices"``,
    ``"faces"`` and optionally ``"self_collision"`` (bool: also test the mesh against itself;
    triangles sharing an edge are never a contact) and ``"name"`` (for messages).
    ``vertices`` is a float32 or float64 array of shape (n, 3); it is the mesh's positions until
    set_positions() is called for it, held like a set_positions() array (a float32 C-contiguous
    array is read in place: changing it moves the mesh). ``faces`` is an integer array of shape
    (m, 3) of vertex indices; contacts name triangles by their row here. Open and non-manifold
    surfaces are fine; a degenerate triangle intersects nothing.
backend : str
    "cpu", "gl" (OpenGL 4.3, any device, software ones included) or "auto" (GL on a hardware
    device, else the CPU; ``notice`` says why).
broadphase : str
    "bvh" (the fastest), "octree-compact", "octree" (the paper's method), "brute" (every pair),
    or "none" (detect() finds nothing). See ``deformcd.broadphases``.
threads : int
    CPU threads; 0 uses every core. Results do not depend on it.
mesh_pairs : sequence of (a, b), optional
    The pairs of meshes to test (a == b: the mesh with itself). By default every pair of
    different meshes, plus each mesh with self_collision with itself.

Raises
------
ValueError
    an array of the wrong dtype or shape, a malformed item.
deformcd.InputError
    a vertex index out of range (naming the mesh and the triangle), a mesh without triangles,
    a pair naming a mesh that does not exist.
deformcd.Error
    an unknown backend or broad-phase name, negative threads.
deformcd.GlError
    backend="gl" without an OpenGL 4.3 context (or a module built without GL).

Thread safety: one Detector may be used from several Python threads; its calls run one at a
time. detect() releases the GIL while it runs (other threads must not write the position
arrays meanwhile).)doc";

constexpr const char* kSetPositionsDoc =
    R"doc(Where mesh `mesh`'s vertex positions are read from, from the next detect() on.

`positions` is a float32 or float64 array of shape (n, 3), n the mesh's vertex count.
A float32 array in native byte order whose rows are packed xyz (C-contiguous, or any row
stride that is a multiple of 4 bytes, e.g. ``V4[:, :3]`` of an (n, 4) array) is NOT copied:
the detector reads it in place at every detect(), so it may be changed in place between
calls, and the detector keeps a reference to it (``positions(mesh) is array``) until the
next set_positions() of that mesh. Any other array (float64, other strides, a list) is
converted once, here, into a float32 array the detector owns; changing the original
afterwards has no effect.

Raises ValueError for a wrong dtype or shape (naming the expected n), deformcd.InputError for
a mesh that does not exist. NaN or infinite positions are reported by detect().)doc";

constexpr const char* kDetectDoc =
    R"doc(One collision pass over the current positions (the arrays are read now). The hierarchies are
built by the first pass (or prepare()), then refitted and rebuilt when needed by each pass.
Releases the GIL while it runs.

Raises deformcd.InputError naming the mesh and the vertex for a NaN or infinite position; the
last results then stay.)doc";

constexpr const char* kContactsDoc =
    R"doc(The intersecting triangle pairs of the last pass as a dict of NumPy arrays,
one row per pair (k rows), sorted by (body_a, face_a, body_b, face_b), with body_a <= body_b
(equal for self-contacts):

- "body_a", "face_a", "body_b", "face_b": int64 (k,): mesh index and triangle row in its faces
- "nodes_a", "nodes_b": int64 (k, 3): the triangles' vertex indices
- "segment": float32 (k, 2, 3): where the triangles cross (both ends equal when they touch at
  a point; zeros for coplanar pairs)
- "coplanar": bool (k,): coplanar triangles overlapping in an area (no segment)

Empty arrays before the first detect().)doc";

}  // namespace

void bind_detector(py::module_& m) {
  py::class_<PyDetector>(m, "Detector", kDetectorDoc)
      .def(py::init<const py::sequence&, const std::string&, const std::string&, int,
                    const py::object&>(),
           py::arg("meshes"), py::arg("backend") = "auto", py::arg("broadphase") = "bvh",
           py::arg("threads") = 0, py::arg("mesh_pairs") = py::none())
      .def("set_positions", &PyDetector::set_positions, py::arg("mesh"), py::arg("positions"),
           kSetPositionsDoc)
      .def("positions", &PyDetector::positions, py::arg("mesh"),
           "The array detect() reads mesh `mesh`'s positions from: the caller's own array when\n"
           "it is read in place, else the detector's float32 copy (which may be changed in place\n"
           "too).")
      .def("detect", &PyDetector::detect, kDetectDoc)
      .def("prepare", &PyDetector::prepare,
           "Builds the hierarchies (BVH, octree boxes) from the current positions now rather\n"
           "than at the first detect(), e.g. to keep that cost out of a timing.")
      .def("contacts", &PyDetector::contacts, kContactsDoc)
      .def("counts", &PyDetector::counts,
           "Counts of the last pass as a dict of ints (all 0 before the first): 'contacts'\n"
           "(intersecting pairs), 'colliding_faces' (triangles in at least one contact),\n"
           "'candidates' (triangle pairs given to the exact test) and 'box_pairs' (overlapping\n"
           "octree leaf-box pairs; 0 for the other methods).")
      .def("face_flags", &PyDetector::face_flags, py::arg("mesh") = py::none(),
           "A bool array, True for each triangle in a contact of the last pass: mesh `mesh`'s\n"
           "triangles (m,), or with mesh=None every mesh's, mesh i's from face_offset(i).")
      .def_property("broadphase", &PyDetector::broadphase, &PyDetector::set_broadphase,
                    "The broad phase detect() runs (a name of deformcd.broadphases); may be "
                    "set between passes.\nEvery one finds the same contacts.")
      .def_property_readonly("mesh_count", &PyDetector::mesh_count, "Number of meshes.")
      .def_property_readonly("face_count", &PyDetector::face_count,
                             "Number of triangles of every mesh.")
      .def("vertex_count", &PyDetector::vertex_count, py::arg("mesh"),
           "The number of vertices of mesh `mesh` (the n of its "
           "positions).")
      .def("faces", &PyDetector::faces, py::arg("mesh"),
           "Mesh `mesh`'s triangles as given: an int64 (m, 3) array (a copy).")
      .def("face_offset", &PyDetector::face_offset, py::arg("mesh"),
           "Where mesh `mesh`'s triangles start in face_flags().")
      .def_property_readonly("backend", &PyDetector::backend, "\"cpu\" or \"gl\".")
      .def_property_readonly("device", &PyDetector::device,
                             "The GL renderer and version, or the CPU thread count.")
      .def_property_readonly("notice", &PyDetector::notice,
                             "Why backend=\"auto\" chose the CPU, if it did; else empty.")
      .def("__repr__", &PyDetector::repr);
}

}  // namespace deformcd::python
