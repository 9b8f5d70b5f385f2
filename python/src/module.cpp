// The contactqp Python module (docs/python.md): pybind11 over the C++ library, for Debian's
// /usr/bin/python3. scipy.sparse and numpy in, numpy out; bad input raises InputError.
#include "bindings.hpp"

#ifndef CONTACTQP_VERSION
#error "CONTACTQP_VERSION is set by python/CMakeLists.txt from the project version"
#endif

PYBIND11_MODULE(contactqp, m) {
  m.doc() = R"(contactqp: frictionless contact as one quadratic program, solved by interchangeable backends.

    minimise  J(u) = 1/2 u^T K u - f^T u   subject to   B u <= g

In the usual QP names (qpsolvers, OSQP): P = K, q = -f, G = B, h = g; the multipliers
lam >= 0 of B u <= g are qpsolvers' z. contactqp.certify() judges any (u, lam) by the same
relative KKT residuals and duality gap, whichever backend produced it.

Two ways in:
  * contactqp.solve_scene("scenes/hertz.json", backend="active_set") runs a scene file as the
    command-line tool does (mesh, QP, solve, certificate, contact pressure, Hertz comparison);
  * contactqp.solve(contactqp.QuadraticProgram(K, f, B, g), backend=...) solves a QP you
    assembled yourself (scipy.sparse K and B, numpy f and g).

Bad input raises contactqp.InputError (a ValueError) naming the field.)";
  m.attr("__version__") = CONTACTQP_VERSION;
  // Nothing of PETSc, MPI or Ipopt is loaded at import: their plugins are opened RTLD_LOCAL when
  // a call first needs them, so another module's MUMPS (GetFEM's) never meets PETSc's MPI build.
  contactqp::python::bind_errors(m);
  contactqp::python::bind_qp(m);
  contactqp::python::bind_pairs(m);
  contactqp::python::bind_scene(m);
}
