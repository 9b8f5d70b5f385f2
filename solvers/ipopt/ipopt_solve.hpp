// The ipopt backend's work, which calls Ipopt (ipopt_solve.cpp): built into the Ipopt plugin.
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// Checks the backend's options and Ipopt's own against Ipopt's list (InputError naming the key).
void check_ipopt_options(const SolveOptions& options);
// The QP by Ipopt: the primal without friction force, Tresca's dual with it, Coulomb by the fixed
// point on Tresca's. One solve at a time in a process (Debian's sequential MUMPS).
SolveResult solve_ipopt(const QuadraticProgram& qp, const SolveOptions& options);

}  // namespace contactqp::detail
