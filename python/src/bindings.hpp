// The parts of the contactqp Python module, one file each (module.cpp puts them together).
#pragma once

#include <pybind11/pybind11.h>

#include <memory>

namespace contactqp {
struct RunReport;
}

namespace contactqp::python {

namespace py = pybind11;

void bind_errors(py::module_& m);  // errors.cpp: contactqp.InputError
void bind_qp(py::module_& m);      // qp_bindings.cpp: Backend, Status, QuadraticProgram, solve, certify
void bind_scene(py::module_& m);   // scene_bindings.cpp: solve_scene, compare_scene and their reports
void bind_pairs(py::module_& m);   // pair_bindings.cpp: PairResult, BodyResult (scenes with several bodies)

// SceneResult.pairs and .bodies (pair_bindings.cpp): one view per pair or body of the report.
py::list pairs_list(const std::shared_ptr<const RunReport>& report);
py::list bodies_list(const std::shared_ptr<const RunReport>& report);

}  // namespace contactqp::python
