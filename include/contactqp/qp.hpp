// The one quadratic program every backend solves, and the vocabulary every backend shares.
//
//     minimise  J(u) = ½ uᵀ K u − fᵀ u     subject to   B u ≤ g
//
// Sign conventions (docs/architecture.md): row i of B is −nᵀ at the displacement DOFs of one
// candidate contact node, g_i = (x_i − p)·n is its initial gap (≥ 0 when not penetrating), and
// the multiplier λ_i ≥ 0 is the nodal contact force, compression positive.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

#include "contactqp/certificate_values.hpp"
#include "contactqp/coarse_space.hpp"
#include "contactqp/friction.hpp"
#include "contactqp/linear_solver.hpp"
#include "contactqp/timer.hpp"

namespace contactqp {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, int indices
using Eigen::VectorXd;

// Where a constraint row came from: metadata for post-processing; backends ignore it.
struct ConstraintRow {
  int node = -1;      // mesh node whose normal displacement the row bounds
  int obstacle = -1;  // index of the obstacle in the scene, or −1 for a row between two bodies
  int pair = -1;      // index of the contact pair in the scene (rows between bodies), or −1
};

struct QuadraticProgram {
  SparseMatrix K;                   // n × n stiffness, symmetric positive (semi)definite, both triangles stored
  VectorXd f;                       // n: load vector (prescribed displacements already moved here)
  SparseMatrix B;                   // m × n: contact rows, −nᵀ at the DOFs of one node each
  VectorXd g;                       // m: initial gaps along the obstacle normal, ≥ 0 unless penetrating
  std::vector<ConstraintRow> rows;  // m entries, or empty when the QP has no mesh behind it
  // n × k rigid-body modes on the free DOFs (k = 3 in 2D), for algebraic multigrid in an
  // iterative solver of K; empty when unknown. Filled by assemble_qp; backends never need it.
  Eigen::MatrixXd near_null_space;
  // n × k, the exact null space of K when K is only positive semidefinite (a body held only by its
  // contacts: its free rigid modes), columns linearly independent; empty (n × 0 or 0 × 0) when K
  // is positive definite. solve() then solves on the range of K and reports the free modes'
  // balance Rᵀ(f − Bᵀλ) (docs/extremes.md, "Bodies held only by their contacts"); when it is
  // empty and K turns out singular, solve() finds it itself from K's eigenvalues.
  Eigen::MatrixXd null_space;
  // Quadratic elements: the P1 level for a multigrid solver of K (coarse_space.hpp); empty for
  // linear elements or when unknown. Filled by assemble_qp; backends never need it.
  CoarseSpace coarse_space;
  // Friction at the contact rows (friction.hpp): empty (law None) for a frictionless problem.
  FrictionBlock friction;

  int n_dofs() const { return static_cast<int>(K.rows()); }
  int n_constraints() const { return static_cast<int>(B.rows()); }
};

// Throws InputError when the shapes disagree ("B has 412 columns, K has 410 rows") or an
// entry is not finite; with friction also when the friction block's sizes disagree with B and
// K, or a threshold or coefficient is negative (friction.hpp). Cheap: O(nnz).
void validate(const QuadraticProgram& qp);

// K u.
VectorXd K_times(const QuadraticProgram& qp, const VectorXd& u);

// J(u) = ½ uᵀKu − fᵀu.
double primal_objective(const QuadraticProgram& qp, const VectorXd& u);

// What kind of problem the QP is, from its friction block: a backend solves only the kinds
// its registration lists (backend.hpp).
ProblemKind problem_kind(const QuadraticProgram& qp);

// An optimisation backend: a small value naming one registration (backend.hpp), compared by
// name, usable as a key of std::map and std::set, printed by to_string. The built-in backends
// register themselves in their own files under solvers/ (and src/petsc/); their names stand
// here so that code can write Backend::ActiveSet. Any other backend (one a program or a test
// registers) comes from register_backend() or parse_backend().
class Backend {
 public:
  // The value an enum had by default: the reference paper's method.
  constexpr Backend() : name_("uzawa") {}

  static const Backend Uzawa;             // dual projected gradient with a fixed step ρ (the reference paper's method)
  static const Backend UzawaAccelerated;  // Uzawa with Nesterov/FISTA extrapolation on the dual and adaptive restart
  static const Backend Ipopt;             // primal interior point (Ipopt with MUMPS) on the QP itself
  static const Backend Nlopt;             // the dual max θ(λ), λ ≥ 0, by a bound-constrained NLopt method
  static const Backend ActiveSet;         // primal-dual active set (semismooth Newton) on the condensed problem
  static const Backend Petsc;             // the bound form solved by PETSc, under mpirun too

  // The name the CLI, the scenes, the JSON and Python use ("active_set").
  constexpr std::string_view name() const { return name_; }

  friend constexpr bool operator==(Backend a, Backend b) { return a.name_ == b.name_; }
  friend constexpr bool operator!=(Backend a, Backend b) { return a.name_ != b.name_; }
  friend constexpr bool operator<(Backend a, Backend b) { return a.name_ < b.name_; }

 private:
  friend class BackendRegistry;
  // `name` must outlive every copy: a string literal, or a name the registry keeps.
  constexpr explicit Backend(std::string_view name) : name_(name) {}
  std::string_view name_;
};

// Constants, initialised at compile time: a SolveOptions made during static initialisation
// (whose default is Backend::Uzawa) needs no registry.
inline constexpr Backend Backend::Uzawa{"uzawa"};
inline constexpr Backend Backend::UzawaAccelerated{"uzawa_accel"};
inline constexpr Backend Backend::Ipopt{"ipopt"};
inline constexpr Backend Backend::Nlopt{"nlopt"};
inline constexpr Backend Backend::ActiveSet{"active_set"};
inline constexpr Backend Backend::Petsc{"petsc"};

// How a solve ended. solve() never claims more than the certificate it computes shows
// (certificate.hpp's certified_status): Converged only when the certificate meets tol.
enum class Status {
  Converged,       // the certificate meets the requested tol (relative KKT residual and duality gap)
  MaxIterations,   // stopped at max_iterations; u and λ are the last (finite) iterate
  Diverged,        // the iteration was expanding (e.g. Uzawa with ρ > ρ_max); stopped early
  NumericalError,  // a factorisation or the backend's library failed; see the message
  Inaccurate,      // the backend stopped on its own test, but the certificate exceeds tol
  Infeasible,      // no u satisfies B u ≤ g: SolveResult::farkas is the evidence
  Unbounded,       // J falls without bound along a free motion: SolveResult::recession is the evidence
};

std::string to_string(Backend backend);  // its name: "uzawa_accel"
std::string to_string(Status status);
// "uzawa" -> Backend::Uzawa, for every registered backend (backend.hpp). Unknown names throw
// InputError(field, "= \"ipot\": unknown backend; valid: uzawa, ...; did you mean \"ipopt\"?").
Backend parse_backend(const std::string& name, const std::string& field = "backend");
// Every registered backend, built in or not (backend_available() tells), in listing order.
std::vector<Backend> all_backends();

// A starting point, e.g. the last load step's answer (quasi-static load paths), in the
// caller's units. Each vector is either empty (no guess) or of its full size: u n, lambda m,
// lambda_t m · n_directions. Backends that can start from it do (uzawa, uzawa_accel and nlopt
// from the multipliers, active_set from the multipliers' active, stick and slip sets, the
// Coulomb fixed point from λ_N's threshold); the others ignore it.
struct InitialGuess {
  VectorXd u, lambda, lambda_t;
  bool empty() const { return u.size() == 0 && lambda.size() == 0 && lambda_t.size() == 0; }
};

// The default iteration limit. With friction a backend may raise it when the caller leaves it
// here (BackendRegistration::friction_max_iterations: uzawa's 50000).
inline constexpr int kDefaultMaxIterations = 10000;

struct SolveOptions {
  Backend backend = Backend::Uzawa;
  double tol = 1e-8;  // relative, dimensionless: each backend's stopping rule uses the scales of certificate.hpp
  int max_iterations = kDefaultMaxIterations;
  bool verbose = false;  // third-party banners and per-iteration logs stay silent unless set
  bool scale = true;     // solve an internally scaled copy, so E and length units do not matter
  // Typed options of one backend, each struct declared beside its backend and read by it alone
  // (contactqp/backends/: UzawaOptions for uzawa and uzawa_accel, NloptOptions, ActiveSetOptions;
  // a backend of yours reads a struct of its own the same way):
  //   options.set(UzawaOptions{UzawaOptions::RhoRule::FractionOfMax, 0.5});
  //   options.get<UzawaOptions>()   // the struct's defaults when none was set
  // backend_options (below) gives the same settings as text; the text wins where both are given.
  template <class Options>
  void set(Options value) {
    typed_options[std::type_index(typeid(Options))] = std::make_shared<const Options>(std::move(value));
  }
  template <class Options>
  Options get() const {
    const auto found = typed_options.find(std::type_index(typeid(Options)));
    return found == typed_options.end() ? Options{} : *static_cast<const Options*>(found->second.get());
  }
  std::map<std::type_index, std::shared_ptr<const void>> typed_options;  // set() and get() read it
  // The solver of K the backends use (linear_solver.hpp, docs/linear-solvers.md). Ipopt
  // factorises its own KKT matrix with MUMPS and ignores it; active_set's condensation
  // is fast with CHOLMOD and takes one solve per contact row with another solver.
  LinearSolverKind linear_solver = LinearSolverKind::Cholmod;
  Ordering ordering = Ordering::Amd;  // fill-reducing ordering of K's factorisation (CHOLMOD)
  // Options of a library underneath, in the library's own syntax, by the library's name: passed
  // through unchanged to the part of contactqp that uses that library (docs/petsc.md: "petsc"
  // holds PETSc's options database entries, from --petsc-options or solver.petsc_options).
  std::map<std::string, std::string> library_options;
  // Backend options as text: Ipopt's own options for ipopt, "algorithm"/"memory" for nlopt.
  // A key "ipopt.print_level" is read only by that backend, so one map can serve several.
  std::map<std::string, std::string> backend_options;  // --backend-option key=value, passed through
  // A solver of this QP's K to reuse (backends that solve with K then skip their own set-up).
  // Load steps keep K: pass the first step's SolveResult::K_factor to the later ones.
  std::shared_ptr<const LinearSolver> K_factor;
  InitialGuess initial;  // warm start; empty: every backend starts from its own default
  // Called by iterative backends with each iterate (k = 1, 2, ...), in the caller's units:
  // for studies of convergence and tests of weak duality. Costs nothing when empty.
  std::function<void(int k, const VectorXd& u, const VectorXd& lambda)> observer;
};

struct SolveResult {
  Status status = Status::NumericalError;          // pessimistic until a backend says otherwise
  std::string message = "solve() was not called";  // why it stopped, one sentence
  VectorXd u, lambda;                              // λ ≥ 0, compression positive; always finite
  // Tangential multipliers (friction.hpp), m · n_directions; empty for a frictionless problem.
  VectorXd lambda_t;
  int iterations = 0;
  Timings timings;  // seconds per phase ("factorize", "solve", ...)
  // Named extras: "rho", "rho_max", ...; Coulomb's "fixed_point_steps" (Tresca solves) and
  // "fixed_point_change" (the last relative change of the threshold μλ_N, ∞-norm).
  std::map<std::string, double> diagnostics;
  // Not failures, but worth telling the user: e.g. a PETSc option nothing read.
  std::vector<std::string> warnings;
  // The solver of K the backend used, if any: reuse it for certify() or further solves.
  std::shared_ptr<const LinearSolver> K_factor;
  // The certificate of (u, λ, λ_T), computed by solve() outside the backend (certificate.hpp);
  // the status never claims more than it shows. Empty only when solve() did not finish.
  std::optional<Certificate> certificate;
  // Status::Infeasible: y ≥ 0 (m entries, ‖y‖∞ = 1) with Bᵀy ≈ 0 and gᵀy < 0, so that no u
  // satisfies B u ≤ g (Farkas' lemma; docs/extremes.md says to what accuracy). Empty otherwise.
  VectorXd farkas;
  // Status::Unbounded: d (n entries, ‖d‖₂ = 1) with K d ≈ 0, B d ≤ 0 and fᵀd > 0: J falls
  // without bound along u + t d, a free motion that the load drives and no row stops. Empty otherwise.
  VectorXd recession;
  // The dimension of K's null space when solve() found K only positive semidefinite (a body free
  // to move rigidly), else 0; solve() looks only when the certificate rejects the answer.
  int null_space_dimension = 0;
};

}  // namespace contactqp
