// The last steps of solve(), the same for every backend (cleanup.cpp explains the rules).
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// For a converged result: λ_i = 0 exactly where row i clearly separates (slack > √tol · L),
// smallest first, as long as the relative stationarity residual stays within max(tol, its value).
// Records the count as the diagnostic "zeroed_multipliers".
void zero_separated_multipliers(const QuadraticProgram& qp, SolveResult& result, double tol);

// True when finite u and λ are still too large to certify: J(u), Bᵀλ or λ_i(Bu − g)_i overflow.
bool overflows(const QuadraticProgram& qp, const SolveResult& result);

}  // namespace contactqp::detail
