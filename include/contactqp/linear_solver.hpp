// The solver of K: everything a backend needs from the stiffness matrix, behind one interface
// (ARCHITECTURE.md, "The solver of K is an axis of its own"). A backend asks "solve K x = b";
// it never names CHOLMOD or PETSc. Implemented by CholeskyFactor (cholesky.hpp: CHOLMOD,
// direct, one process) and by any solver a library registers for its kind (register_linear_solver:
// src/petsc/ registers PETSc's KSP, iterative, CG + GAMG by default). docs/linear-solvers.md
// describes the choice, its options and the inner tolerance.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contactqp/coarse_space.hpp"

namespace contactqp {

// Which library solves with K (SolveOptions::linear_solver, --linear-solver, solver.linear_solver).
enum class LinearSolverKind {
  Cholmod,  // sparse Cholesky by CHOLMOD: direct, exact to round-off, one process
  Petsc,    // PETSc's KSP (CG + GAMG with the rigid-body near-null space by default): iterative
};

std::string to_string(LinearSolverKind kind);  // "cholmod", "petsc"
// "petsc" -> LinearSolverKind::Petsc. Unknown names throw InputError(field, "... valid: cholmod, petsc").
LinearSolverKind parse_linear_solver(const std::string& name, const std::string& field);
std::vector<LinearSolverKind> all_linear_solvers();   // every enum value, in declaration order
bool linear_solver_available(LinearSolverKind kind);  // false when its library was not built in

// The fill-reducing ordering of a direct factorisation. Measured on the Hertz meshes up to
// 1.1e6 DOFs (README, "Orderings"), AMD gives the fastest analyse + factorise + solve (or within
// noise), so SolveOptions defaults to it; METIS needs about 30% less memory for L at 1e6 DOFs.
enum class Ordering {
  Auto,   // CHOLMOD's default: AMD, and METIS as well when AMD's fill is high; the better one wins
  Amd,    // approximate minimum degree only: the cheapest analysis
  Metis,  // METIS nested dissection only: less fill and flops on large 2D meshes, slower analysis
};

std::string to_string(Ordering ordering);  // "auto", "amd", "metis"
// "amd" -> Ordering::Amd. Unknown names throw InputError(field, "... valid: auto, amd, metis").
Ordering parse_ordering(const std::string& name, const std::string& field);

// C A⁻¹ Cᵀ and C A⁻¹ b for a sparse C with few rows: the condensed operator of contact rows.
struct Condensation {
  Eigen::MatrixXd S;              // C A⁻¹ Cᵀ (m × m), symmetric positive semidefinite
  Eigen::VectorXd c;              // C A⁻¹ b (m)
  long long reached_columns = 0;  // CHOLMOD: columns of L on the elimination-tree paths of C's rows
  long long entries = 0;          // CHOLMOD: entries of W = L⁻¹ P Cᵀ computed (dense blocks per supernode)
  long long peak_entries = 0;     // CHOLMOD: the most of them held at once
};

// What a solver of K reports about itself.
struct LinearSolverStatistics {
  std::string name;               // "cholmod", "petsc"
  std::string method;             // e.g. "supernodal LLᵀ, amd ordering" or "cg + gamg"
  double setup_seconds = 0;       // analyse + factorise, or matrix copy + preconditioner set-up
  long long factor_nonzeros = 0;  // nnz(L) of a direct solver, 0 for an iterative one
  long long solves = 0;           // right-hand sides solved so far
  long long iterations = 0;       // Krylov iterations summed over those solves; 0 for a direct solver
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;

  // True when the set-up succeeded and no solve has failed since. A solver never throws on a
  // numerical failure: backends check ok() (after a loop is enough: a failed solve returns a
  // finite vector) and report message() as the outcome.
  virtual bool ok() const = 0;
  // Empty when ok(); otherwise one sentence, e.g. "not positive definite: ..." or
  // "KSP did not converge: KSP_DIVERGED_ITS after 10000 iterations".
  virtual const std::string& message() const = 0;
  virtual int size() const = 0;

  // x = A⁻¹ b. An iterative solver stops at its inner tolerance (docs/linear-solvers.md).
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) const = 0;
  // The same, starting an iterative solver from `guess` (e.g. the previous iterate of an outer
  // loop, which is close when the right-hand sides change little); a direct solver ignores it.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const;
  // One solve per column; a solver may do better (CHOLMOD solves them together).
  virtual Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& b) const;

  // S = C A⁻¹ Cᵀ and c = C A⁻¹ b. Generic: solves with the columns of Cᵀ, in blocks, then
  // symmetrises S. CholeskyFactor overrides it with a restricted forward solve (far cheaper).
  virtual Condensation condense(const Eigen::SparseMatrix<double>& C, const Eigen::VectorXd& b) const;

  // The same solver standing for the matrix c·A (solves divide by c); shares the set-up.
  std::shared_ptr<const LinearSolver> scaled(double c) const { return scaled_solver(c); }

  virtual LinearSolverStatistics statistics() const = 0;
  // The fill-reducing ordering a direct solver used ("amd", "metis", ...); "none" otherwise.
  virtual std::string ordering_name() const { return "none"; }
  // Things the user should know that are not failures (e.g. a PETSc option nobody read).
  virtual std::vector<std::string> warnings() const { return {}; }

 protected:
  virtual std::shared_ptr<const LinearSolver> scaled_solver(double c) const = 0;
};

// How to build a solver of K (SolveOptions carries the same choices; see qp.hpp).
struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::Cholmod;
  Ordering ordering = Ordering::Amd;  // direct solvers
  // The outer (backend's) relative tolerance: an iterative solver derives its inner stopping
  // rule from it so that the certificate still holds at tol (docs/linear-solvers.md).
  double tol = 1e-8;
  // n × k near-null space of A (rigid-body modes on the free DOFs), for algebraic multigrid;
  // empty when unknown. Not referenced after construction.
  Eigen::MatrixXd near_null_space;
  // Quadratic elements: the P1 level (coarse_space.hpp) for a multigrid with a p-level; empty
  // otherwise. Not referenced after construction.
  CoarseSpace coarse_space;
  // Options of the library that solves, in its own syntax, by library name (SolveOptions::
  // library_options, passed on unchanged).
  std::map<std::string, std::string> library_options;
  bool verbose = false;  // let the library print its own log
};

// Sets up a solver of A (symmetric positive definite; both triangles stored) of the chosen
// kind. Never throws on a numerical failure (check ok()); throws InputError when the kind was
// not built into this copy of contactqp or its options are bad input.
std::shared_ptr<const LinearSolver> make_linear_solver(const Eigen::SparseMatrix<double>& A,
                                                       const LinearSolverOptions& options);

// How a library that solves with K offers itself for a kind other than CHOLMOD's: its file
// registers a factory (CONTACTQP_BUILTIN, as backends register), and make_linear_solver() and
// linear_solver_available() find it. The factory follows make_linear_solver()'s rules.
using LinearSolverFactory = std::function<std::shared_ptr<const LinearSolver>(const Eigen::SparseMatrix<double>& A,
                                                                              const LinearSolverOptions& options)>;
void register_linear_solver(LinearSolverKind kind, LinearSolverFactory factory);

}  // namespace contactqp
