// The `deformcd` Python module: errors, mesh files, and the Detector and World bindings.

#include <filesystem>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include "array_conversion.h"
#include "bindings.h"
#include "deformcd/collision.h"
#include "deformcd/error.h"
#include "deformcd/io.h"
#include "deformcd/world.h"

namespace deformcd::python {

namespace {

py::tuple read_surface_arrays(const std::filesystem::path& file) {
  const SurfaceMesh mesh = read_surface(file);
  py::array_t<double> vertices({static_cast<py::ssize_t>(mesh.vertices.size()), py::ssize_t{3}});
  double* v = vertices.mutable_data();
  for (const glm::dvec3& p : mesh.vertices) {
    *v++ = p.x;
    *v++ = p.y;
    *v++ = p.z;
  }
  return py::make_tuple(vertices, triangle_array(mesh.triangles));
}

// A blow-up's site (SimulationError::site()) as attributes of the Python exception, so that a
// study's row can hold them without parsing the message; an unknown field is None.
void raise_simulation_error(const py::handle& type, const SimulationError& e) {
  const BlowUpSite& site = e.site();
  py::object error = type(e.what());
  error.attr("stage") = site.stage;
  if (site.frame >= 0) error.attr("frame") = site.frame;
  if (site.body >= 0) {
    error.attr("body") = site.body;
    error.attr("body_name") = site.body_name;
  }
  if (site.node >= 0) error.attr("node") = site.node;
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

// Translators are tried last registered first: the base class goes first.
void bind_errors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  error.doc() =
      "Base of every error deformcd raises on purpose (a subclass of RuntimeError); the message "
      "states\nthe broken contract and, for input, where.";
  static py::exception<InputError> input(m, "InputError", error.ptr());
  input.doc() =
      "Bad input: a malformed file (\"FILE:LINE: message\"), an index out of range (\"mesh 1: "
      "triangle 7 ...\"),\na non-finite position (\"mesh 0: vertex 3 ...\"), a bad scene key.";
  static py::exception<GlError> gl(m, "GlError", error.ptr());
  gl.doc() = "No OpenGL 4.3 compute context could be had (backend=\"gl\"), or GL failed.";
  static py::exception<SimulationError> simulation(m, "SimulationError", error.ptr());
  simulation.doc() =
      "A World's simulation blew up (NaN/Inf, or a node moving implausibly far in one "
      "substep); the\nmessage names the body and the frame and suggests a smaller dt or more "
      "substeps.\n\nAttributes (SimulationError::site() in C++), None when not known: stage "
      "(\"simulation\" "
      "or\n\"response\": the contact response), frame (the frame being stepped, from 1), body "
      "(index),\nbody_name, node (index in the body).";
  for (const char* field : {"frame", "body", "body_name", "node"})
    simulation.attr(field) = py::none();
  simulation.attr("stage") = "simulation";
  // By value: pybind11 takes a void (*)(std::exception_ptr).
  py::register_exception_translator([](std::exception_ptr p) {  // NOLINT(performance-*)
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SimulationError& e) {
      raise_simulation_error(simulation, e);
    } catch (const GlError& e) {
      gl(e.what());
    } catch (const InputError& e) {
      input(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace deformcd::python

// _deformcd: the compiled part of the `deformcd` package, whose __init__.py re-exports it.
PYBIND11_MODULE(_deformcd, m) {
  namespace py = pybind11;
  using namespace deformcd::python;
  m.doc() = R"doc(deformcd: collision detection for deformable triangle meshes, and mass-spring
simulation of deformable bodies, on the CPU (multithreaded) or OpenGL 4.3 compute shaders.

- Detector: your meshes (NumPy vertices and faces), your positions (read in place from your
  float32 arrays), the intersecting triangle pairs back as NumPy arrays.
- World: a scene file's bodies simulated and stepped from Python.
- read_surface(path): a mesh file (OFF, OBJ, STL, PLY) as (vertices, faces) arrays.

Errors: deformcd.Error (a RuntimeError) and its subclasses InputError, GlError and
SimulationError, with the C++ library's messages; ValueError for an array of the wrong dtype,
shape or length, naming the argument.)doc";
  m.attr("__version__") = DEFORMCD_VERSION;
#ifdef DEFORMCD_HAS_GL
  m.attr("has_gl") = true;
#else
  m.attr("has_gl") = false;
#endif
  py::tuple broadphases(deformcd::broadphase_names().size());
  for (std::size_t i = 0; i < deformcd::broadphase_names().size(); ++i)
    broadphases[i] = deformcd::broadphase_names()[i];
  m.attr("broadphases") = broadphases;
  m.attr("backends") = py::make_tuple("auto", "gl", "cpu");

  bind_errors(m);
  m.def("read_surface", &read_surface_arrays, py::arg("path"),
        R"doc(Reads a triangulated surface file: OFF, OBJ, STL or PLY (ASCII or binary).
Returns vertices, float64 (n, 3), in the file's order (STL's equal corners welded), and faces,
int64 (m, 3), polygons fan-triangulated in file order: the numbering `deformcd collide` uses.
Raises deformcd.InputError naming the file, the line and what is wrong.)doc");
  bind_detector(m);
  bind_world(m);
}
