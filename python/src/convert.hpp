// Python values in and out of the library's types, with bad input reported as InputError
// naming the argument (the same channel as the C++ library: docs/style.md, "Bad input").
#pragma once

#include <pybind11/pybind11.h>

#include <map>
#include <string>
#include <vector>

#include "contactqp/backends/uzawa.hpp"
#include "contactqp/post.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::python {

namespace py = pybind11;

// A 1-D array of finite or non-finite doubles (finiteness is checked by the library). Accepts
// anything numpy.asarray turns into a 1-D float array; InputError(field, ...) otherwise.
VectorXd to_vector(py::handle value, const std::string& field);

// Any scipy.sparse matrix (every format: converted to CSC) or a 2-D numpy array. Duplicate
// entries are summed, as scipy does.
SparseMatrix to_sparse(py::handle value, const std::string& field);

// Eigen column-major sparse matrix to scipy.sparse.csc_matrix (a copy).
py::object to_scipy(const SparseMatrix& matrix);

// A contactqp.Backend or the name of a registered backend ("uzawa", "active_set", ...).
Backend to_backend(py::handle value, const std::string& field);

// The Uzawa step: None or "auto", a positive number (absolute ρ), or a fraction of ρ_max
// written "0.5x".
UzawaOptions to_rho(py::handle value, const std::string& field);

// A dict {key: str | int | float} into text, as the scene file's solver.options are read.
std::map<std::string, std::string> to_backend_options(py::handle value, const std::string& field);

// The solver settings shared by solve(), solve_scene() and compare_scene(): each argument that
// is not None replaces the value in `options` (InputError naming the argument otherwise).
struct SolverArguments {
  py::object backend, tol, rho, max_iterations, verbose, backend_options, scale;
};
void apply(const SolverArguments& arguments, SolveOptions& options);

// A positive integer (e.g. max_elements); InputError(field, ...) for anything else.
long long to_positive_integer(py::handle value, const std::string& field);

// Seconds per phase as a dict, in the order the phases were recorded.
py::dict to_dict(const Timings& timings);

// An observer callable held for the length of one solve. The C++ side copies the
// std::function freely (also without the GIL), so it captures only a pointer to this object,
// which owns the Python reference. An exception raised by the callable stops the observing
// (not the solve) and is raised again by rethrow_if_failed() once the solve has returned.
class Observer {
 public:
  Observer(py::object callable, const std::string& field);  // None: no observer
  void install(SolveOptions& options);                      // sets options.observer when there is a callable
  void rethrow_if_failed();                                 // with the GIL held

 private:
  py::object callable_;
  std::unique_ptr<py::error_already_set> error_;
};

// (s, pressure) per node of a contact profile, as the JSON writes it: an N x 2 array.
Eigen::MatrixXd profile_array(const std::vector<ContactProfilePoint>& profile);

}  // namespace contactqp::python
