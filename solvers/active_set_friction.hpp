// The active_set backend on a frictional problem (friction_ssn.hpp): condense the stacked rows
// C = [B; T] once, solve the condensed Tresca problem by semismooth Newton (Coulomb: the fixed
// point of coulomb_fixed_point.hpp on the same condensed S, each step warm-started), recover u
// with one solve.
#pragma once

#include "contactqp/backends/active_set.hpp"
#include "contactqp/qp.hpp"

namespace contactqp::detail {

SolveResult solve_active_set_friction(const QuadraticProgram& qp, const SolveOptions& options,
                                      const ActiveSetOptions& settings);

}  // namespace contactqp::detail
