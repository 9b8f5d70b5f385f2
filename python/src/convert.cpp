#include "convert.hpp"

#include <pybind11/numpy.h>

#include <cmath>
#include <vector>

#include "contactqp/errors.hpp"
#include "contactqp/scene.hpp"

namespace contactqp::python {
namespace {

std::string type_name(py::handle value) { return py::str(py::type::of(value).attr("__name__")); }

std::string shape_text(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

// numpy.asarray(value, dtype=float), or InputError when numpy cannot make numbers of it.
py::array_t<double> float_array(py::handle value, const std::string& field) {
  try {
    py::object numpy = py::module_::import("numpy");
    return numpy.attr("ascontiguousarray")(value, py::arg("dtype") = numpy.attr("float64"));
  } catch (py::error_already_set&) {
    throw InputError(field, "is a " + type_name(value) + ": must be an array of numbers");
  }
}

}  // namespace

VectorXd to_vector(py::handle value, const std::string& field) {
  if (value.is_none()) throw InputError(field, "is None: must be a 1-D array of numbers");
  const py::array_t<double> array = float_array(value, field);
  if (array.ndim() != 1) throw InputError(field, "has shape " + shape_text(array) + ": must be a 1-D array");
  VectorXd vector(array.shape(0));
  const auto view = array.unchecked<1>();
  for (py::ssize_t i = 0; i < array.shape(0); ++i) vector[i] = view(i);
  return vector;
}

namespace {

// A dense 2-D array's nonzeros (summing nothing: each entry is one position).
SparseMatrix from_dense(const py::array_t<double>& dense) {
  const auto d = dense.unchecked<2>();
  std::vector<Eigen::Triplet<double>> entries;
  for (py::ssize_t i = 0; i < dense.shape(0); ++i)
    for (py::ssize_t j = 0; j < dense.shape(1); ++j)
      if (d(i, j) != 0) entries.emplace_back(static_cast<int>(i), static_cast<int>(j), d(i, j));
  SparseMatrix matrix(static_cast<Eigen::Index>(dense.shape(0)), static_cast<Eigen::Index>(dense.shape(1)));
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

// scipy.sparse if a script has imported it, else None. A scipy matrix cannot exist before its
// module is imported, and importing it for a numpy array would cost 0.1-0.15 s of start-up.
py::object scipy_sparse_if_imported() {
  const py::dict modules = py::module_::import("sys").attr("modules");
  return modules.contains("scipy.sparse") ? py::object(modules["scipy.sparse"]) : py::object(py::none());
}

}  // namespace

SparseMatrix to_sparse(py::handle value, const std::string& field) {
  if (value.is_none()) throw InputError(field, "is None: must be a scipy.sparse matrix or a 2-D array");
  const py::object sparse = scipy_sparse_if_imported();
  if (sparse.is_none() || !py::bool_(sparse.attr("issparse")(value))) {
    const py::array_t<double> dense = float_array(value, field);
    if (dense.ndim() != 2)
      throw InputError(field, "has shape " + shape_text(dense) + ": must be a 2-D matrix (scipy.sparse or numpy)");
    return from_dense(dense);
  }
  const py::object csc = sparse.attr("csc_matrix")(value);
  const py::tuple shape = csc.attr("shape");
  const long rows = shape[0].cast<long>(), cols = shape[1].cast<long>();
  const py::array_t<double> data = float_array(csc.attr("data"), field + ".data");
  py::object numpy = py::module_::import("numpy");
  const auto as_index = [&](py::handle a) {
    return py::array_t<long long>(numpy.attr("ascontiguousarray")(a, py::arg("dtype") = numpy.attr("int64")));
  };
  const py::array_t<long long> indices = as_index(csc.attr("indices")), indptr = as_index(csc.attr("indptr"));
  const auto d = data.unchecked<1>();
  const auto r = indices.unchecked<1>();
  const auto p = indptr.unchecked<1>();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(data.shape(0));
  for (long c = 0; c < cols; ++c)
    for (long long k = p(c); k < p(c + 1); ++k) entries.emplace_back(static_cast<int>(r(k)), static_cast<int>(c), d(k));
  SparseMatrix matrix(rows, cols);
  matrix.setFromTriplets(entries.begin(), entries.end());  // sums duplicates, like scipy
  matrix.makeCompressed();
  return matrix;
}

py::object to_scipy(const SparseMatrix& matrix) {
  SparseMatrix m = matrix;
  m.makeCompressed();
  py::array_t<double> data(m.nonZeros());
  py::array_t<int> indices(m.nonZeros()), indptr(m.cols() + 1);
  std::copy(m.valuePtr(), m.valuePtr() + m.nonZeros(), data.mutable_data());
  std::copy(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros(), indices.mutable_data());
  std::copy(m.outerIndexPtr(), m.outerIndexPtr() + m.cols() + 1, indptr.mutable_data());
  return py::module_::import("scipy.sparse")
      .attr("csc_matrix")(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(m.rows(), m.cols()));
}

Backend to_backend(py::handle value, const std::string& field) {
  if (py::isinstance<py::str>(value)) return parse_backend(value.cast<std::string>(), field);
  try {
    return value.cast<Backend>();
  } catch (const py::cast_error&) {
    throw InputError(field, "is a " + type_name(value) + ": must be a contactqp.Backend or its name");
  }
}

UzawaOptions to_rho(py::handle value, const std::string& field) {
  if (value.is_none()) return {};
  if (py::isinstance<py::str>(value)) return parse_rho(value.cast<std::string>(), field);
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)))
    throw InputError(
        field, "is a " + type_name(value) + ": must be \"auto\", a number, or a fraction of rho_max such as \"0.5x\"");
  UzawaOptions rho;
  rho.rho_rule = UzawaOptions::RhoRule::Absolute;
  rho.rho = value.cast<double>();
  require(rho.rho > 0 && std::isfinite(rho.rho), field, rho.rho, "must be a positive number");
  return rho;
}

std::map<std::string, std::string> to_backend_options(py::handle value, const std::string& field) {
  std::map<std::string, std::string> options;
  if (value.is_none()) return options;
  if (!py::isinstance<py::dict>(value))
    throw InputError(field, "is a " + type_name(value) + ": must be a dict {\"key\": value}");
  for (const auto& [key, entry] : value.cast<py::dict>()) {
    const std::string name = py::str(key);
    if (py::isinstance<py::str>(entry))
      options[name] = entry.cast<std::string>();
    else if (!py::isinstance<py::bool_>(entry) &&
             (py::isinstance<py::int_>(entry) || py::isinstance<py::float_>(entry)))
      options[name] = py::str(py::repr(entry));
    else
      throw InputError(field + "." + name,
                       "= " + std::string(py::str(py::repr(entry))) + ": must be a string or a number");
  }
  return options;
}

void apply(const SolverArguments& arguments, SolveOptions& options) {
  if (!arguments.backend.is_none()) options.backend = to_backend(arguments.backend, "backend");
  if (!arguments.tol.is_none()) {
    if (py::isinstance<py::bool_>(arguments.tol) ||
        !(py::isinstance<py::float_>(arguments.tol) || py::isinstance<py::int_>(arguments.tol)))
      throw InputError("tol", "is a " + type_name(arguments.tol) + ": must be a number in (0, 1)");
    options.tol = arguments.tol.cast<double>();
    require(options.tol > 0 && options.tol < 1, "tol", options.tol, "must lie in (0, 1)");
  }
  if (!arguments.rho.is_none()) options.set(to_rho(arguments.rho, "rho"));
  if (!arguments.max_iterations.is_none()) {
    if (py::isinstance<py::bool_>(arguments.max_iterations) || !py::isinstance<py::int_>(arguments.max_iterations))
      throw InputError("max_iterations",
                       "is a " + type_name(arguments.max_iterations) + ": must be a positive integer");
    const long long n = to_positive_integer(arguments.max_iterations, "max_iterations");
    require(n <= 2147483647LL, "max_iterations", n, "must be a positive integer below 2^31");
    options.max_iterations = static_cast<int>(n);
  }
  if (!arguments.verbose.is_none()) options.verbose = py::bool_(arguments.verbose);
  if (!arguments.scale.is_none()) options.scale = py::bool_(arguments.scale);
  for (const auto& [key, value] : to_backend_options(arguments.backend_options, "backend_options"))
    options.backend_options[key] = value;
}

long long to_positive_integer(py::handle value, const std::string& field) {
  if (py::isinstance<py::bool_>(value) || !py::isinstance<py::int_>(value))
    throw InputError(field, "is a " + type_name(value) + ": must be a positive integer");
  long long n = 0;
  try {
    n = value.cast<long long>();
  } catch (const py::cast_error&) {
    throw InputError(field, "= " + std::string(py::str(value)) + ": must be a positive integer below 2^63");
  }
  require(n > 0, field, n, "must be positive");
  return n;
}

py::dict to_dict(const Timings& timings) {
  py::dict out;
  for (const auto& [phase, seconds] : timings.phases()) out[py::str(phase)] = seconds;
  return out;
}

Observer::Observer(py::object callable, const std::string& field) : callable_(std::move(callable)) {
  if (!callable_.is_none() && !PyCallable_Check(callable_.ptr()))
    throw InputError(field, "is a " + type_name(callable_) + ": must be callable as observer(k, u, lam)");
}

void Observer::install(SolveOptions& options) {
  if (callable_.is_none()) return;
  Observer* self = this;  // the std::function holds a pointer only: copying it needs no GIL
  options.observer = [self](int k, const VectorXd& u, const VectorXd& lambda) {
    py::gil_scoped_acquire gil;
    if (self->error_) return;
    try {
      self->callable_(k, py::array_t<double>(u.size(), u.data()), py::array_t<double>(lambda.size(), lambda.data()));
    } catch (py::error_already_set& error) {
      self->error_ = std::make_unique<py::error_already_set>(std::move(error));
    }
  };
}

void Observer::rethrow_if_failed() {
  if (error_) {
    py::error_already_set error = std::move(*error_);
    error_.reset();
    throw error;
  }
}

Eigen::MatrixXd profile_array(const std::vector<ContactProfilePoint>& profile) {
  Eigen::MatrixXd out(profile.size(), 2);
  for (size_t i = 0; i < profile.size(); ++i) out.row(i) << profile[i].s, profile[i].pressure;
  return out;
}

}  // namespace contactqp::python
