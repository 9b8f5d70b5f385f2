// contactqp.QuadraticProgram, solve(), certify(), and the Backend and Status enums: any
// user's assembled contact QP, solved by every backend and judged by one certificate.
#include <pybind11/eigen.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <memory>
#include <string_view>

#include "bindings.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/solve.hpp"
#include "convert.hpp"

namespace contactqp::python {
namespace {

// K must be symmetric: the backends and certify() read one triangle or the other. Round-off
// of an assembly (a few ulps of the largest entry) passes; a wrong matrix does not.
constexpr double kSymmetryTolerance = 1e-10;

void check_finite_matrix(const SparseMatrix& matrix, const std::string& field) {
  for (int c = 0; c < matrix.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(matrix, c); it; ++it)
      if (!std::isfinite(it.value()))
        throw InputError(field, "[" + std::to_string(it.row()) + ", " + std::to_string(it.col()) +
                                    "] = " + format_value(it.value()) + ": every entry must be finite");
}

void check_finite_vector(const VectorXd& vector, const std::string& field) {
  for (Eigen::Index i = 0; i < vector.size(); ++i)
    if (!std::isfinite(vector[i]))
      throw InputError(field,
                       "[" + std::to_string(i) + "] = " + format_value(vector[i]) + ": every entry must be finite");
}

std::string shape(const SparseMatrix& m) {
  return "(" + std::to_string(m.rows()) + ", " + std::to_string(m.cols()) + ")";
}

QuadraticProgram make_qp(py::handle K_in, py::handle f_in, py::handle B_in, py::handle g_in, py::handle R_in) {
  QuadraticProgram qp;
  qp.K = to_sparse(K_in, "K");
  qp.f = to_vector(f_in, "f");
  const long n = qp.K.rows();
  if (qp.K.cols() != n) throw InputError("K", "has shape " + shape(qp.K) + ": must be square");
  if (n == 0) throw InputError("K", "has shape 0 x 0: a problem needs at least one unknown");
  if (qp.f.size() != n)
    throw InputError("f", "has " + std::to_string(qp.f.size()) + " entries, K has " + std::to_string(n) + " rows");
  if (B_in.is_none() != g_in.is_none())
    throw InputError(
        B_in.is_none() ? "B" : "g",
        "= None: must be given with " + std::string(B_in.is_none() ? "g" : "B") + " (both None: no constraints)");
  if (B_in.is_none()) {
    qp.B = SparseMatrix(0, n);
    qp.g = VectorXd(0);
  } else {
    qp.B = to_sparse(B_in, "B");
    qp.g = to_vector(g_in, "g");
  }
  if (qp.B.cols() != n)
    throw InputError("B", "has " + std::to_string(qp.B.cols()) + " columns, K has " + std::to_string(n) + " rows");
  if (qp.g.size() != qp.B.rows())
    throw InputError("g",
                     "has " + std::to_string(qp.g.size()) + " entries, B has " + std::to_string(qp.B.rows()) + " rows");
  check_finite_matrix(qp.K, "K");
  check_finite_vector(qp.f, "f");
  check_finite_matrix(qp.B, "B");
  check_finite_vector(qp.g, "g");
  const double scale = n > 0 && qp.K.nonZeros() > 0 ? qp.K.coeffs().cwiseAbs().maxCoeff() : 0.0;
  const SparseMatrix asymmetry = qp.K - SparseMatrix(qp.K.transpose());
  const double worst = asymmetry.nonZeros() > 0 ? asymmetry.coeffs().cwiseAbs().maxCoeff() : 0.0;
  if (worst > kSymmetryTolerance * scale)
    throw InputError("K", "is not symmetric: max |K - K^T| = " + format_value(worst) + " against max |K| = " +
                              format_value(scale) + " (the stiffness must be symmetric positive definite)");
  if (!R_in.is_none()) {
    // A 1-D array is one mode; a 2-D array holds one mode per column (n × k).
    py::object array = py::module_::import("numpy").attr("asarray")(R_in, "float64");
    const py::tuple dims = array.attr("shape");
    if (dims.size() < 1 || dims.size() > 2 || dims[0].cast<long>() != n)
      throw InputError("null_space", "has shape " + py::repr(dims).cast<std::string>() + ", K has " +
                                         std::to_string(n) + " rows: one mode per column, n x k");
    if (dims.size() == 1) array = array.attr("reshape")(n, 1);
    qp.null_space = array.cast<Eigen::MatrixXd>();
  }
  validate(qp);  // the library's own checks, the same for every caller
  return qp;
}

// A solve's outcome with its certificate, as Python sees it.
struct Solution {
  Backend backend = Backend::Uzawa;
  SolveResult result;
  Certificate certificate;
};

void check_iterate(const QuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda) {
  if (u.size() != qp.n_dofs())
    throw InputError("u",
                     "has " + std::to_string(u.size()) + " entries, K has " + std::to_string(qp.n_dofs()) + " rows");
  if (lambda.size() != qp.n_constraints())
    throw InputError("lam", "has " + std::to_string(lambda.size()) + " entries, B has " +
                                std::to_string(qp.n_constraints()) + " rows");
  check_finite_vector(u, "u");
  check_finite_vector(lambda, "lam");
}

py::dict certificate_dict(const Certificate& c) {
  py::dict out;
  out["stationarity"] = c.stationarity;
  out["primal_feasibility"] = c.primal_feasibility;
  out["dual_feasibility"] = c.dual_feasibility;
  out["complementarity"] = c.complementarity;
  out["kkt_max"] = c.kkt_max();
  out["objective"] = c.objective;
  out["dual_available"] = c.dual_available;
  out["dual_objective"] = c.dual_available ? py::object(py::float_(c.dual_objective)) : py::none();
  out["duality_gap"] = c.dual_available ? py::object(py::float_(c.duality_gap)) : py::none();
  out["relative_gap"] = c.dual_available ? py::object(py::float_(c.relative_gap)) : py::none();
  return out;
}

const char* const kSolveDoc = R"(Solve the QP  min 1/2 u^T K u - f^T u  s.t.  B u <= g  with one backend.

Arguments (None keeps the library's default, shown in brackets):
  qp              a contactqp.QuadraticProgram
  backend         a contactqp.Backend or its name ("uzawa", "active_set", ...: every name in
                  contactqp.Backend.__members__, in lower case) [uzawa]
  tol             relative tolerance in (0, 1) of the backend's stopping rule, measured with
                  the certificate's scales [1e-8]
  rho             Uzawa's step: "auto", a positive number, or a fraction of rho_max like "0.5x" [auto]
  max_iterations  positive iteration limit [10000; uzawa on a frictional problem 50000]
  observer        callable observer(k, u, lam), called with each iterate (numpy copies, in
                  your units) by the iterative backends; an exception it raises stops the
                  observing and is raised again when the solve returns
  verbose         let the backend print its own log [False]
  backend_options dict of backend options, e.g. {"ipopt.print_level": 5} or {"algorithm": "LD_MMA"}
  scale           solve an internally scaled copy, so units do not matter [True]

Returns a contactqp.Solution (u, lam, status, message, iterations, timings, diagnostics,
certificate). The GIL is released during the solve. Bad input raises contactqp.InputError.

Example:
  >>> import numpy as np, scipy.sparse as sp, contactqp
  >>> K = sp.csc_matrix([[2.0, -1.0], [-1.0, 2.0]])
  >>> qp = contactqp.QuadraticProgram(K, f=np.array([1.0, 1.0]), B=np.array([[1.0, 0.0]]), g=np.array([0.5]))
  >>> s = contactqp.solve(qp, backend="active_set", tol=1e-10)
  >>> s.status, s.u, s.lam          # u = (0.5, 0.75), lam = (0.75,)
)";

// The class constant of a backend: its name in upper case (UZAWA_ACCEL).
std::string constant_name(Backend backend) {
  std::string name = to_string(backend);
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
  return name;
}

}  // namespace

void bind_qp(py::module_& m) {
  // contactqp.Backend: a class constant per registered backend (Backend.ACTIVE_SET), listed in
  // __members__ in listing order as the enum it once was; Backend("active_set") by name.
  py::class_<Backend> backend_class(m, "Backend",
                                    "An optimisation backend (contactqp.available_backends() lists those built in).");
  backend_class
      .def(py::init([](const std::string& name) { return parse_backend(name, "backend"); }), py::arg("name"),
           "The backend of this name, e.g. Backend('active_set'); InputError for an unknown one.")
      .def_property_readonly(
          "label", [](Backend b) { return to_string(b); },
          "The name the command line and scene files use, e.g. 'active_set'.")
      .def_property_readonly("name", &constant_name, "The constant's name, e.g. 'ACTIVE_SET'.")
      .def_property_readonly(
          "summary", [](Backend b) { return backend_registration(b)->summary; }, "What the method is, in one line.")
      .def(py::self == py::self)
      .def(py::self != py::self)
      .def("__hash__", [](Backend b) { return std::hash<std::string_view>()(b.name()); })
      .def("__repr__", [](Backend b) { return "<Backend." + constant_name(b) + ": '" + to_string(b) + "'>"; })
      .def("__str__", [](Backend b) { return "Backend." + constant_name(b); });
  py::dict members;
  for (Backend backend : all_backends()) {
    backend_class.attr(constant_name(backend).c_str()) = backend;
    members[constant_name(backend).c_str()] = backend;
  }
  backend_class.attr("__members__") = members;
  py::enum_<Status>(m, "Status", "How a solve ended; never more than the certificate shows.")
      .value("CONVERGED", Status::Converged, "the certificate meets the requested tol (10 x tol for round-off)")
      .value("MAX_ITERATIONS", Status::MaxIterations, "stopped at max_iterations; u and lam are the last iterate")
      .value("DIVERGED", Status::Diverged, "the iteration was expanding (e.g. Uzawa with rho > rho_max)")
      .value("NUMERICAL_ERROR", Status::NumericalError, "a factorisation or the backend's library failed")
      .value("INACCURATE", Status::Inaccurate,
             "the backend stopped on its own test, but the certificate of its answer exceeds tol")
      .value("INFEASIBLE", Status::Infeasible, "no u satisfies B u <= g: Solution.farkas is the evidence")
      .value("UNBOUNDED", Status::Unbounded,
             "the load drives a free motion no row stops: Solution.recession is the evidence")
      .def_property_readonly(
          "label", [](Status s) { return to_string(s); }, "The name the result JSON uses, e.g. 'converged'.");

  m.def(
      "available_backends", []() { return available_backends(); },
      "The backends built into this copy, in listing order (Backend.__members__'s).");
  m.def(
      "backend_available", [](py::handle backend) { return backend_available(to_backend(backend, "backend")); },
      py::arg("backend"), "True when the backend's library was built in (a Backend or its name).");

  py::class_<QuadraticProgram, std::shared_ptr<QuadraticProgram>>(m, "QuadraticProgram", R"(A contact QP

    minimise  1/2 u^T K u - f^T u   subject to   B u <= g

K (n x n, symmetric positive definite) and B (m x n) are scipy.sparse matrices of any format
or 2-D numpy arrays; f (n) and g (m) are 1-D arrays. B and g may both be None (no constraints).
In qpsolvers' names: P = K, q = -f, G = B, h = g. The data are copied; the object is immutable.)")
      .def(py::init([](py::object K, py::object f, py::object B, py::object g, py::object null_space) {
             return std::make_shared<QuadraticProgram>(make_qp(K, f, B, g, null_space));
           }),
           py::arg("K"), py::arg("f"), py::arg("B") = py::none(), py::arg("g") = py::none(),
           py::arg("null_space") = py::none(),
           "QuadraticProgram(K, f, B=None, g=None, null_space=None); null_space (n x k, or one mode of n) "
           "spans K's null space when K is only semidefinite (bodies held by their contacts; solve() finds it "
           "itself when it is not given). InputError names the argument on a wrong shape, a non-finite entry, "
           "a K that is not symmetric or a null_space column K does not annihilate.")
      .def_property_readonly(
          "K", [](const QuadraticProgram& qp) { return to_scipy(qp.K); }, "K as scipy.sparse.csc_matrix (a copy)")
      .def_property_readonly(
          "f", [](const QuadraticProgram& qp) { return qp.f; }, "f (a copy)")
      .def_property_readonly(
          "B", [](const QuadraticProgram& qp) { return to_scipy(qp.B); }, "B as scipy.sparse.csc_matrix (a copy)")
      .def_property_readonly(
          "g", [](const QuadraticProgram& qp) { return qp.g; }, "g (a copy)")
      .def_property_readonly(
          "null_space",
          [](const QuadraticProgram& qp) {
            return qp.null_space.cols() > 0 ? Eigen::MatrixXd(qp.null_space) : Eigen::MatrixXd(qp.n_dofs(), 0);
          },
          "K's null space as given (n x k; k = 0 when none was)")
      .def_property_readonly("n_dofs", &QuadraticProgram::n_dofs, "n, the number of unknowns")
      .def_property_readonly("n_constraints", &QuadraticProgram::n_constraints, "m, the number of rows of B")
      .def(
          "objective",
          [](const QuadraticProgram& qp, py::handle u) {
            const VectorXd x = to_vector(u, "u");
            check_iterate(qp, x, VectorXd::Zero(qp.n_constraints()));
            return primal_objective(qp, x);
          },
          py::arg("u"), "J(u) = 1/2 u^T K u - f^T u.")
      .def("__repr__", [](const QuadraticProgram& qp) {
        return "<contactqp.QuadraticProgram n_dofs=" + std::to_string(qp.n_dofs()) +
               " n_constraints=" + std::to_string(qp.n_constraints()) + ">";
      });

  py::class_<Certificate>(m, "Certificate", R"(The backend-independent optimality certificate of (u, lam).

Relative KKT residuals (stationarity, primal_feasibility, dual_feasibility, complementarity,
kkt_max), J(u) (objective), theta(lam) (dual_objective), the gap J - theta (duality_gap) and
its relative value (relative_gap); the dual quantities are None when K cannot be factorised.
The scales are documented in include/contactqp/certificate.hpp.)")
      .def_readonly("stationarity", &Certificate::stationarity, "||Ku - f + B^T lam||_inf / force scale")
      .def_readonly("primal_feasibility", &Certificate::primal_feasibility, "||max(0, Bu - g)||_inf / length scale")
      .def_readonly("dual_feasibility", &Certificate::dual_feasibility, "||max(0, -lam)||_inf, relative")
      .def_readonly("complementarity", &Certificate::complementarity, "max |lam_i (Bu - g)_i|, relative")
      .def_readonly("objective", &Certificate::objective, "J(u), in the QP's energy units")
      .def_readonly("dual_available", &Certificate::dual_available, "False when K could not be factorised")
      .def_property_readonly(
          "dual_objective",
          [](const Certificate& c) { return c.dual_available ? py::object(py::float_(c.dual_objective)) : py::none(); },
          "theta(lam), or None")
      .def_property_readonly(
          "duality_gap",
          [](const Certificate& c) { return c.dual_available ? py::object(py::float_(c.duality_gap)) : py::none(); },
          "J(u) - theta(lam), or None")
      .def_property_readonly(
          "relative_gap",
          [](const Certificate& c) { return c.dual_available ? py::object(py::float_(c.relative_gap)) : py::none(); },
          "duality_gap / energy scale, or None")
      .def_property_readonly("kkt_max", &Certificate::kkt_max, "the largest of the four relative KKT residuals")
      .def("as_dict", &certificate_dict, "Every number above in a dict.")
      .def("__repr__", [](const Certificate& c) {
        return "<contactqp.Certificate kkt_max=" + format_value(c.kkt_max()) +
               (c.dual_available ? " relative_gap=" + format_value(c.relative_gap) : std::string()) + ">";
      });

  py::class_<Solution>(m, "Solution", R"(The outcome of contactqp.solve(): u (also x), lam (also z),
status, message, iterations, timings (seconds per phase), diagnostics (e.g. rho, rho_max),
certificate, backend, and converged (status == Status.CONVERGED).)")
      .def_property_readonly(
          "u", [](const Solution& s) { return s.result.u; }, "the displacements (primal solution)")
      .def_property_readonly(
          "x", [](const Solution& s) { return s.result.u; }, "u, under qpsolvers' name")
      .def_property_readonly(
          "lam", [](const Solution& s) { return s.result.lambda; },
          "the multipliers of B u <= g, >= 0 (contact forces)")
      .def_property_readonly(
          "z", [](const Solution& s) { return s.result.lambda; }, "lam, under qpsolvers' name")
      .def_property_readonly("status", [](const Solution& s) { return s.result.status; })
      .def_property_readonly("converged", [](const Solution& s) { return s.result.status == Status::Converged; })
      .def_property_readonly(
          "message", [](const Solution& s) { return s.result.message; }, "why it stopped, one sentence")
      .def_property_readonly("iterations", [](const Solution& s) { return s.result.iterations; })
      .def_property_readonly(
          "timings", [](const Solution& s) { return to_dict(s.result.timings); }, "seconds per phase")
      .def_property_readonly(
          "diagnostics", [](const Solution& s) { return s.result.diagnostics; }, "named extras: rho, rho_max, ...")
      .def_property_readonly("backend", [](const Solution& s) { return s.backend; })
      .def_readonly("certificate", &Solution::certificate)
      .def_property_readonly(
          "farkas",
          [](const Solution& s) { return s.result.farkas.size() ? py::object(py::cast(s.result.farkas)) : py::none(); },
          "INFEASIBLE: y >= 0 with B^T y ~ 0 and g^T y < 0 (no u satisfies B u <= g), else None")
      .def_property_readonly(
          "recession",
          [](const Solution& s) {
            return s.result.recession.size() ? py::object(py::cast(s.result.recession)) : py::none();
          },
          "UNBOUNDED: d with K d ~ 0, B d <= 0 and f^T d > 0 (the energy falls along it), else None")
      .def_property_readonly(
          "null_space_dimension", [](const Solution& s) { return s.result.null_space_dimension; },
          "the dimension of K's null space when solve() found K only semidefinite, else 0")
      .def("__repr__", [](const Solution& s) {
        return "<contactqp.Solution backend=" + to_string(s.backend) + " status=" + to_string(s.result.status) +
               " iterations=" + std::to_string(s.result.iterations) +
               " kkt_max=" + format_value(s.certificate.kkt_max()) + ">";
      });

  m.def(
      "solve",
      [](const QuadraticProgram& qp, py::object backend, py::object tol, py::object rho, py::object max_iterations,
         py::object observer, py::object verbose, py::object backend_options, py::object scale) {
        SolveOptions options;
        apply({backend, tol, rho, max_iterations, verbose, backend_options, scale}, options);
        Observer watch(observer, "observer");
        watch.install(options);
        validate_options(options);
        Solution solution;
        solution.backend = options.backend;
        {
          py::gil_scoped_release release;
          solution.result = solve(qp, options);
          solution.certificate = solution.result.certificate ? *solution.result.certificate
                                                             : certify(qp, solution.result.u, solution.result.lambda,
                                                                       solution.result.K_factor.get());
          solution.result.K_factor.reset();
        }
        watch.rethrow_if_failed();
        return solution;
      },
      py::arg("qp"), py::kw_only(), py::arg("backend") = py::none(), py::arg("tol") = py::none(),
      py::arg("rho") = py::none(), py::arg("max_iterations") = py::none(), py::arg("observer") = py::none(),
      py::arg("verbose") = py::none(), py::arg("backend_options") = py::none(), py::arg("scale") = py::none(),
      kSolveDoc);

  m.def(
      "certify",
      [](const QuadraticProgram& qp, py::handle u_in, py::handle lam_in) {
        const VectorXd u = to_vector(u_in, "u");
        const VectorXd lambda = to_vector(lam_in, "lam");
        check_iterate(qp, u, lambda);
        py::gil_scoped_release release;
        return certify(qp, u, lambda);
      },
      py::arg("qp"), py::arg("u"), py::arg("lam"),
      R"(The certificate of any (u, lam) for qp: relative KKT residuals, J(u), theta(lam) and the gap.

Example:
  >>> c = contactqp.certify(qp, u, lam)
  >>> c.kkt_max, c.relative_gap
)");
}

}  // namespace contactqp::python
