#pragma once
// The parts of the `deformcd` module, each adding its classes and functions to it.

#include <pybind11/pybind11.h>

namespace deformcd::python {

namespace py = pybind11;

// deformcd.Error, InputError, GlError, SimulationError (in module.cpp).
void bind_errors(py::module_& m);
// deformcd.Detector.
void bind_detector(py::module_& m);
// deformcd.World.
void bind_world(py::module_& m);

}  // namespace deformcd::python
