// Internal scaling of the QP, so that the backends see numbers of order one whatever units
// the scene uses (E from 1e-6 to 1e12, lengths from 1e-6 to 1e3).
//
// With a stiffness scale κ and a displacement scale s the scaled problem is
//   K̃ = K/κ,  f̃ = f/(κ s),  B̃ = B,  g̃ = g/s,   and its solution is  ũ = u/s,  λ̃ = λ/(κ s).
// The friction block: T̃ = T, offset/s, threshold/(κ s), μ unchanged; λ̃_T = λ_T/(κ s).
// Every relative residual of certificate.hpp is invariant under this change, so a backend's
// tolerance means the same thing in both. A Uzawa step ρ (force per length) becomes ρ/κ.
#pragma once

#include "contactqp/qp.hpp"

namespace contactqp::detail {

struct QpScaling {
  double stiffness = 1.0;     // κ: the largest diagonal entry of K
  double displacement = 1.0;  // s: ‖f‖∞/κ, or ‖g‖∞ when f = 0, or 1
};

// From K's diagonal (KOperations::diagonal: a problem held in parts sums its parts'), f and g.
QpScaling choose_scaling(const QuadraticProgram& qp, const VectorXd& K_diagonal);
QuadraticProgram scaled_qp(const QuadraticProgram& qp, const QpScaling& scaling);
SolveOptions scaled_options(const SolveOptions& options, const QpScaling& scaling);
// Maps a result of the scaled QP back to the caller's units (u, λ, λ_T, ρ-type diagnostics, factor).
void unscale_result(SolveResult& result, const QpScaling& scaling);

}  // namespace contactqp::detail
