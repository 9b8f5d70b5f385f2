// A QP whose K has a null space: bodies that only their contacts hold (docs/extremes.md,
// "Bodies held only by their contacts").
//
// With R (n × k, orthonormal) spanning K's null space, the QP has a solution when the rows can
// balance the load on every free mode, Rᵀ(f − Bᵀλ) = 0, and each backend would need its own
// treatment of a singular K (a generalised inverse, a projector, a null space on the matrix).
// solve() instead runs every backend on a sequence of definite problems, the proximal point
// method on the free modes' coordinates:
//
//   K_ε = K + ε Σ_{j∈F} e_j e_jᵀ,   f_k = f + ε Σ_{j∈F} a_k,j e_j,   a_{k+1} = u_k restricted to F
//
// F holds k fixing DOFs (R restricted to F invertible: a column-pivoted QR of Rᵀ picks them),
// so K_ε is positive definite and only f changes from one step to the next: the solver of
// K_ε is set up once and each step starts from the last answer. The springs' force
// ε (u_F − a_k) is all that the original problem's stationarity lacks, and it vanishes as the
// steps converge (each contracts the error of the free modes by about ε / (ε + c), c the
// stiffness with which the contacts hold the body; ε is 0.1 of K's diagonal at F, and Anderson
// mixing of the anchors a_k makes the convergence about k + 1 steps where the active set holds). The
// certificate of the original QP decides when to stop; θ is then evaluated with K's
// generalised inverse (K with the fixing DOFs removed), exact where λ balances every free mode.
// A free mode that no active row sees (a frictionless ball's sideways translation, which the
// load does not drive) keeps its start; at the end the answer takes the smallest norm over such
// modes when that keeps the certificate (frictionless problems).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "contactqp/linear_solver.hpp"
#include "contactqp/qp.hpp"
#include "solve_steps.hpp"

namespace contactqp::detail {

// Orthonormal columns spanning those of R (Householder QR). Throws InputError naming `field`
// when the columns are linearly dependent.
Eigen::MatrixXd orthonormal_null_space(const Eigen::MatrixXd& R, const char* field);

// k = R.cols() DOFs on which R's rows form an invertible (well-conditioned) k × k block: the
// first k pivots of a column-pivoted QR of Rᵀ. Fixing them removes every free mode of K.
std::vector<int> fixing_dofs(const Eigen::MatrixXd& R);

// K's generalised inverse: solve(y) = x with x_F = 0 and K x = y whenever Rᵀy = 0, from one
// factorisation of K without the rows and columns F (positive definite when F fixes every
// free mode). Its condense() works on the same reduced K.
std::shared_ptr<const LinearSolver> generalised_inverse(const SparseMatrix& K, const std::vector<int>& fixed,
                                                        const LinearSolverOptions& options);

// The relative spring stiffness of the proximal steps, their most, and the memory of the
// Anderson mixing that accelerates them. ε trades the steps' count (each contracts the free
// modes' error by about ε / (ε + c) before mixing) against the conditioning of K_ε, which the
// dual backends feel most: uzawa's ρ falls with 1/λ_max(B K_ε⁻¹ Bᵀ) ~ ε.
inline constexpr double kProximalRelative = 0.1;
inline constexpr int kProximalMaxSteps = 50;
inline constexpr int kAndersonMemory = 6;      // at most; min(6, k) differences are kept
inline constexpr int kProximalSoftenings = 4;  // ε / 10 each time the steps stall (near gross slip)

// One backend run on a definite QP (solve.cpp's run_backend with that QP's own K).
using DefiniteSolve = std::function<SolveResult(const QuadraticProgram& qp, const SolveOptions& options)>;

// The proximal steps above for qp with null space R (orthonormal), each solved by `run`; the
// result carries the certificate of the original QP (computed with the generalised inverse,
// which is also its K_factor), Converged only when that certificate meets options.tol, and the
// diagnostics "proximal_steps", "free_modes" and "rigid_balance" (‖Rᵀ(f − Bᵀλ − Tᵀλ_T)‖∞
// relative to the force scale: the free modes' equilibrium). K applies qp's K (solve_steps.hpp):
// on a problem held in parts (qp.K this process's part, R, f, B and g whole on every process)
// every step is collective and every decision is taken alike on every process, from summed
// products; the springs join the part of the process that K.adds_springs names. There the
// generalised inverse comes only from the first step's solver of K_ε (a backend that returns
// none leaves the certificate without its dual).
SolveResult solve_with_free_modes(const QuadraticProgram& qp, const Eigen::MatrixXd& R, const SolveOptions& options,
                                  const KOperations& K, const DefiniteSolve& run);

}  // namespace contactqp::detail
