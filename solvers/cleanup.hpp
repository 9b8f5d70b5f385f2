// The last steps of solve(), the same for every backend (cleanup.cpp explains the rules).
#pragma once

#include <functional>

#include "contactqp/qp.hpp"

namespace contactqp::detail {

// For a converged result: λ_i = 0 exactly where row i clearly separates (slack > √tol · L),
// smallest first, as long as the relative stationarity residual stays within max(tol, its value).
// Records the count as the diagnostic "zeroed_multipliers".
// K_times gives K u (solve_steps.hpp's KOperations::times).
using KTimes = std::function<VectorXd(const VectorXd& u)>;
void zero_separated_multipliers(const QuadraticProgram& qp, const KTimes& K_times, SolveResult& result, double tol);

// True when finite u and λ are still too large to certify: J(u), Bᵀλ or λ_i(Bu − g)_i overflow.
bool overflows(const QuadraticProgram& qp, const KTimes& K_times, const SolveResult& result);

}  // namespace contactqp::detail
