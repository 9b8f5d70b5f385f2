// The parts of the contactqp Python module, one file each (module.cpp puts them together).
#pragma once

#include <pybind11/pybind11.h>

namespace contactqp::python {

namespace py = pybind11;

void bind_errors(py::module_& m);  // errors.cpp: contactqp.InputError
void bind_qp(py::module_& m);      // qp_bindings.cpp: Backend, Status, QuadraticProgram, solve, certify
void bind_scene(py::module_& m);   // scene_bindings.cpp: solve_scene, compare_scene and their reports

}  // namespace contactqp::python
