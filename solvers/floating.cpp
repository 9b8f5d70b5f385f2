// Proximal steps on the free modes of a semidefinite K (floating.hpp).
#include "floating.hpp"

#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "backends.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
#include "qp/dense_decompositions.hpp"
#include "qp/no_solution.hpp"
#include "qp/norms.hpp"

namespace contactqp::detail {
namespace {

// P (n × (n − |F|)) keeps the DOFs outside F, in order: K_r = Pᵀ K P, C_r = C P, b_r = Pᵀ b.
SparseMatrix keep_matrix(int n, const std::vector<int>& fixed, std::vector<int>& kept) {
  std::vector<char> is_fixed(static_cast<size_t>(n), 0);
  for (int j : fixed) is_fixed[static_cast<size_t>(j)] = 1;
  kept.clear();
  for (int i = 0; i < n; ++i)
    if (!is_fixed[static_cast<size_t>(i)]) kept.push_back(i);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(kept.size());
  for (size_t c = 0; c < kept.size(); ++c) entries.emplace_back(kept[c], static_cast<int>(c), 1.0);
  SparseMatrix P(n, static_cast<long>(kept.size()));
  P.setFromTriplets(entries.begin(), entries.end());
  return P;
}

// K⁺ through a solver of the reduced K (floating.hpp).
class GeneralisedInverse : public LinearSolver {
 public:
  GeneralisedInverse(std::shared_ptr<const LinearSolver> reduced, SparseMatrix keep)
      : reduced_(std::move(reduced)), keep_(std::move(keep)) {}

  bool ok() const override { return !reduced_ || reduced_->ok(); }
  const std::string& message() const override { return reduced_ ? reduced_->message() : empty_; }
  int size() const override { return static_cast<int>(keep_.rows()); }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override {
    if (!reduced_) return Eigen::VectorXd::Zero(b.size());
    return keep_ * reduced_->solve(Eigen::VectorXd(keep_.transpose() * b));
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const override {
    if (!reduced_) return Eigen::VectorXd::Zero(b.size());
    return keep_ * reduced_->solve(Eigen::VectorXd(keep_.transpose() * b), Eigen::VectorXd(keep_.transpose() * guess));
  }
  Condensation condense(const SparseMatrix& C, const Eigen::VectorXd& b) const override {
    if (!reduced_) {
      Condensation none;
      none.S = Eigen::MatrixXd::Zero(C.rows(), C.rows());
      none.c = Eigen::VectorXd::Zero(C.rows());
      return none;
    }
    return reduced_->condense(SparseMatrix(C * keep_), Eigen::VectorXd(keep_.transpose() * b));
  }
  LinearSolverStatistics statistics() const override {
    LinearSolverStatistics s = reduced_ ? reduced_->statistics() : LinearSolverStatistics{};
    s.method = "generalised inverse (K without its " + std::to_string(keep_.rows() - keep_.cols()) + " fixing DOFs)" +
               (s.method.empty() ? "" : ": " + s.method);
    return s;
  }
  std::string ordering_name() const override { return reduced_ ? reduced_->ordering_name() : "none"; }

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override {
    return std::make_shared<GeneralisedInverse>(reduced_ ? reduced_->scaled(c) : nullptr, keep_);
  }

 private:
  std::shared_ptr<const LinearSolver> reduced_;  // null when every DOF is fixed (K = 0)
  SparseMatrix keep_;
  std::string empty_;
};

// K⁺ from a solver of K_ε = K + ε Σ_F e_j e_jᵀ, without a factorisation of its own: x = K_ε⁻¹ b
// corrected by W C⁻¹ x_F (W = K_ε⁻¹ E_F, C = E_Fᵀ W, k × k) has x_F = 0 and K x = b off F, which
// is the reduced K's solution: one solve of K_ε per solve, and k to set it up.
class GeneralisedInverseOfShifted : public LinearSolver {
 public:
  GeneralisedInverseOfShifted(std::shared_ptr<const LinearSolver> shifted, std::vector<int> fixed)
      : shifted_(std::move(shifted)), fixed_(std::move(fixed)) {
    const int n = shifted_->size();
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n, static_cast<long>(fixed_.size()));
    for (size_t j = 0; j < fixed_.size(); ++j) E(fixed_[j], static_cast<long>(j)) = 1;
    W_ = shifted_->solve_columns(E);
    C_ = Eigen::MatrixXd(static_cast<long>(fixed_.size()), static_cast<long>(fixed_.size()));
    for (size_t i = 0; i < fixed_.size(); ++i) C_.row(static_cast<long>(i)) = W_.row(fixed_[i]);
    C_lu_ = C_.partialPivLu();
  }

  bool ok() const override { return shifted_->ok(); }
  const std::string& message() const override { return shifted_->message(); }
  int size() const override { return shifted_->size(); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const override { return corrected(shifted_->solve(b)); }
  Eigen::VectorXd solve(const Eigen::VectorXd& b, const Eigen::VectorXd& guess) const override {
    return corrected(shifted_->solve(b, guess));
  }
  LinearSolverStatistics statistics() const override { return shifted_->statistics(); }
  std::string ordering_name() const override { return shifted_->ordering_name(); }

 protected:
  std::shared_ptr<const LinearSolver> scaled_solver(double c) const override {
    // (c K_ε)⁻¹ = K_ε⁻¹ / c scales W and C alike: the correction is the same fraction of x.
    return std::make_shared<GeneralisedInverseOfShifted>(shifted_->scaled(c), fixed_);
  }

 private:
  Eigen::VectorXd corrected(Eigen::VectorXd x) const {
    Eigen::VectorXd at_fixed(static_cast<long>(fixed_.size()));
    for (size_t j = 0; j < fixed_.size(); ++j) at_fixed[static_cast<long>(j)] = x[fixed_[j]];
    x -= W_ * C_lu_.solve(at_fixed);
    for (int j : fixed_) x[j] = 0;  // exactly, not to round-off
    return x;
  }

  std::shared_ptr<const LinearSolver> shifted_;
  std::vector<int> fixed_;
  Eigen::MatrixXd W_, C_;
  Eigen::PartialPivLU<Eigen::MatrixXd> C_lu_;
};

// u restricted to the fixing DOFs.
Eigen::VectorXd at(const Eigen::VectorXd& u, const std::vector<int>& dofs) {
  Eigen::VectorXd out(static_cast<long>(dofs.size()));
  for (size_t j = 0; j < dofs.size(); ++j) out[static_cast<long>(j)] = u[dofs[j]];
  return out;
}

// ‖Rᵀ(f − Bᵀλ − Tᵀλ_T)‖∞ over the force scale: how far λ is from balancing the load on every
// free mode (zero at a solution; with R orthonormal it never exceeds √n times the stationarity).
double rigid_balance(const QuadraticProgram& qp, const Eigen::MatrixXd& R, const KOperations& K,
                     const SolveResult& result) {
  const Eigen::VectorXd Btl = qp.B.transpose() * result.lambda;
  Eigen::VectorXd r = qp.f - Btl;
  double F = force_scale(qp.f, K.times(result.u), Btl);  // K u summed over the parts, if any
  if (!qp.friction.empty() && result.lambda_t.size() == qp.friction.T.rows()) {
    const Eigen::VectorXd Ttl = qp.friction.T.transpose() * result.lambda_t;
    r -= Ttl;
    F = std::max(F, Ttl.cwiseAbs().maxCoeff());
  }
  const double balance = (R.transpose() * r).cwiseAbs().maxCoeff();
  return F > 0 ? balance / F : balance;
}

// The stated choice for the free modes no active row sees (floating.hpp): u minus its component
// along them, kept when the certificate still meets tol. Returns how many such modes there are.
int take_smallest_norm(const QuadraticProgram& qp, const Eigen::MatrixXd& R, const KOperations& K,
                       const LinearSolver* K_plus, double tol, SolveResult& result) {
  if (!qp.friction.empty()) return 0;
  std::vector<int> active;
  for (int i = 0; i < result.lambda.size(); ++i)
    if (result.lambda[i] > 0) active.push_back(i);
  const Eigen::MatrixXd BR = Eigen::MatrixXd(qp.B * R);
  Eigen::MatrixXd seen(static_cast<long>(active.size()), R.cols());
  for (size_t a = 0; a < active.size(); ++a) seen.row(static_cast<long>(a)) = BR.row(active[a]);
  // Rows of B have unit norm and R orthonormal columns: singular values of at most √m.
  Eigen::MatrixXd unseen;
  if (seen.rows() == 0) {
    unseen = Eigen::MatrixXd::Identity(R.cols(), R.cols());
  } else {
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(seen, Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    long rank = 0;
    for (long j = 0; j < sigma.size(); ++j)
      if (sigma[j] > 1e-8) ++rank;
    unseen = svd.matrixV().rightCols(R.cols() - rank);
  }
  if (unseen.cols() == 0) return 0;
  const Eigen::MatrixXd D = R * unseen;  // orthonormal
  SolveResult moved = result;
  moved.u -= D * (D.transpose() * result.u);
  const Certificate certificate = K.certify(moved.u, moved.lambda, Eigen::VectorXd(), K_plus);
  if (meets_tolerance(certificate, tol)) {
    result.u = moved.u;
    result.certificate = certificate;
  }
  return static_cast<int>(unseen.cols());
}

// Anderson acceleration of the fixed-point map a ↦ T(a) = u_F of the step anchored at a (Walker
// & Ni 2011, the difference form): T is affine while the active set holds, and there the mixing
// finds the fixed point in about k + 1 steps where plain steps contract by ε / (ε + c) each. A
// step whose residual grows restarts the history (the active set changed).
class AndersonMixing {
 public:
  explicit AndersonMixing(int memory) : memory_(memory) {}

  Eigen::VectorXd next(const Eigen::VectorXd& a, const Eigen::VectorXd& Ta) {
    const Eigen::VectorXd r = Ta - a;
    if (has_last_ && r.norm() > last_r_.norm()) {
      da_.clear();
      dr_.clear();
    } else if (has_last_) {
      da_.push_back(a - last_a_);
      dr_.push_back(r - last_r_);
      if (static_cast<int>(da_.size()) > memory_) {
        da_.erase(da_.begin());
        dr_.erase(dr_.begin());
      }
    }
    last_a_ = a;
    last_r_ = r;
    has_last_ = true;
    if (dr_.empty()) return Ta;
    const long p = static_cast<long>(dr_.size());
    Eigen::MatrixXd DA(a.size(), p), DR(a.size(), p);
    for (long j = 0; j < p; ++j) {
      DA.col(j) = da_[static_cast<size_t>(j)];
      DR.col(j) = dr_[static_cast<size_t>(j)];
    }
    const Eigen::VectorXd gamma = DR.colPivHouseholderQr().solve(r);  // least squares min ‖r − DR γ‖
    const Eigen::VectorXd mixed = Ta - (DA + DR) * gamma;
    // A mixed anchor that does not move (a degenerate fit) would repeat the last step: take the plain one.
    if (!mixed.allFinite() || mixed == a) {
      da_.clear();
      dr_.clear();
      return Ta;
    }
    return mixed;
  }

 private:
  int memory_;
  std::vector<Eigen::VectorXd> da_, dr_;
  Eigen::VectorXd last_a_, last_r_;
  bool has_last_ = false;
};

}  // namespace

Eigen::MatrixXd orthonormal_null_space(const Eigen::MatrixXd& R, const char* field) {
  if (R.cols() == 0) return R;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> pivoted(R);
  pivoted.setThreshold(1e-10);
  if (pivoted.rank() < R.cols())
    throw InputError(field, "has linearly dependent columns (rank " + std::to_string(pivoted.rank()) + " of " +
                                std::to_string(R.cols()) + ")");
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(R);
  return qr.householderQ() * Eigen::MatrixXd::Identity(R.rows(), R.cols());
}

std::vector<int> fixing_dofs(const Eigen::MatrixXd& R) {
  const Eigen::MatrixXd Rt = R.transpose();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Rt);
  std::vector<int> fixed;
  for (long j = 0; j < R.cols(); ++j) fixed.push_back(qr.colsPermutation().indices()[j]);
  std::sort(fixed.begin(), fixed.end());
  return fixed;
}

std::shared_ptr<const LinearSolver> generalised_inverse(const SparseMatrix& K, const std::vector<int>& fixed,
                                                        const LinearSolverOptions& options) {
  std::vector<int> kept;
  SparseMatrix keep = keep_matrix(static_cast<int>(K.rows()), fixed, kept);
  if (kept.empty()) return std::make_shared<GeneralisedInverse>(nullptr, keep);
  LinearSolverOptions reduced = options;
  if (options.near_null_space.rows() == K.rows())
    reduced.near_null_space = Eigen::MatrixXd(keep.transpose() * options.near_null_space);
  reduced.coarse_space = CoarseSpace{};  // the P1 level's rows would need the same restriction
  const SparseMatrix K_reduced = SparseMatrix(keep.transpose() * K * keep);
  return std::make_shared<GeneralisedInverse>(make_linear_solver(K_reduced, reduced), keep);
}

namespace {

// Gross slip: a free motion that only friction holds (no normal row stops it), loaded along it
// by more than friction can hold (Q > μP: no equilibrium; the springs of the proximal steps carry
// the excess and their anchors move by it over ε every step). `moved` is the anchors' last move
// on F; its motion r = R c (R_F c = moved) is checked: its drive rᵀ(f − Bᵀλ) against friction's
// most along it, Σ_i bound_i ‖(T r)_i‖ (bound μ_i λ_i, or Tresca's threshold), at the last λ.
// The message and r (unit length) when the drive exceeds it; nothing otherwise.
std::optional<std::string> gross_slip(const QuadraticProgram& qp, const Eigen::MatrixXd& R,
                                      const std::vector<int>& fixed, const Eigen::VectorXd& moved,
                                      const SolveResult& result, Eigen::VectorXd& direction) {
  const FrictionBlock& friction = qp.friction;
  if (friction.empty() || R.cols() == 0 || !(moved.cwiseAbs().maxCoeff() > 0) || result.lambda.size() != qp.B.rows() ||
      friction.T.rows() == 0)
    return std::nullopt;
  // The motions no normal row sees (B R z = 0), and of them the one nearest the anchors' move.
  Eigen::MatrixXd unseen = Eigen::MatrixXd::Identity(R.cols(), R.cols());
  if (qp.B.rows() > 0) {
    const Eigen::MatrixXd BR = qp.B * R;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(BR, Eigen::ComputeFullV);
    long rank = 0;
    for (long j = 0; j < svd.singularValues().size(); ++j) rank += svd.singularValues()[j] > 1e-9 * std::sqrt(R.rows());
    unseen = svd.matrixV().rightCols(R.cols() - rank);
  }
  if (unseen.cols() == 0) return std::nullopt;
  const Eigen::MatrixXd R0 = R * unseen;
  Eigen::MatrixXd R0_F(static_cast<long>(fixed.size()), R0.cols());
  for (size_t j = 0; j < fixed.size(); ++j) R0_F.row(static_cast<long>(j)) = R0.row(fixed[j]);
  Eigen::VectorXd r = R0 * R0_F.colPivHouseholderQr().solve(moved);
  if (!(r.norm() > 0)) return std::nullopt;
  r /= r.norm();
  r /= r.cwiseAbs().maxCoeff();  // a unit motion (a translation by 1): drive and most are forces
  const double drive = r.dot(qp.f - qp.B.transpose() * result.lambda);
  const Eigen::VectorXd Tr = friction.T * r;
  const int d = friction.n_directions;
  double most = 0;
  for (long i = 0; i < qp.B.rows(); ++i) {
    const double bound =
        friction.law == FrictionLaw::Coulomb ? friction.coefficient[i] * result.lambda[i] : friction.threshold[i];
    most += std::max(0.0, bound) * Tr.segment(i * d, d).norm();
  }
  if (!(drive > most * (1 + 1e-6)) || !(drive > 1e-12 * qp.f.cwiseAbs().maxCoeff())) return std::nullopt;
  direction = r / r.norm();
  return "unbounded: gross slip: the load along a free motion that only friction holds (" + short_number(drive) +
         ") exceeds the most friction holds along it (" + short_number(most) +
         (friction.law == FrictionLaw::Coulomb ? ", the coefficient times the normal forces)"
                                               : ", the Tresca thresholds)");
}

}  // namespace

SolveResult solve_with_free_modes(const QuadraticProgram& qp, const Eigen::MatrixXd& R, const SolveOptions& options,
                                  const KOperations& K, const DefiniteSolve& run) {
  Stopwatch clock;
  const std::vector<int> fixed = fixing_dofs(R);
  const int n = qp.n_dofs();

  // ε: kProximalRelative of K's diagonal where the free modes move, Σ R_j² K_jj / Σ R_j² (of ‖K‖∞
  // where that is zero; 1 when K = 0, where any ε gives the same steps up to the scaling solve()
  // applies). Not the diagonal at F alone: a DOF that a whole rigid surface shares (model.hpp's
  // RigidSurface) may be picked, and its diagonal is the surface's — Hertz by force on a surface
  // turned by 30° then did not settle in 9 steps (5 with this mean; docs/extremes.md).
  const Eigen::VectorXd K_diagonal = K.diagonal();  // summed over the parts, if any
  double diagonal = 0, weight = 0;
  for (long j = 0; j < K_diagonal.size(); ++j) {
    const double r2 = R.row(j).squaredNorm();
    diagonal += r2 * std::abs(K_diagonal[j]);
    weight += r2;
  }
  diagonal = weight > 0 ? diagonal / weight : 0.0;
  double epsilon = kProximalRelative * diagonal;
  // Where the free modes move K has no stiffness at all: the scale of K elsewhere.
  if (!(epsilon > 0))
    epsilon = kProximalRelative *
              (K.whole ? infinity_norm(qp.K) : (K_diagonal.size() > 0 ? K_diagonal.cwiseAbs().maxCoeff() : 0.0));
  if (!(epsilon > 0) || !std::isfinite(epsilon)) epsilon = 1.0;

  QuadraticProgram inner = qp;
  inner.null_space.resize(0, 0);
  // K_ε's springs on F, in one process's part when K is held in parts (K.adds_springs).
  const auto add_springs = [&inner, &fixed, &K](double stiffness) {
    if (!K.adds_springs) return;
    for (int j : fixed) inner.K.coeffRef(j, j) += stiffness;
    inner.K.makeCompressed();
  };
  add_springs(epsilon);

  SolveOptions inner_options = options;
  inner_options.K_factor = nullptr;  // the caller's, if any, stands for K, not K_ε
  Eigen::VectorXd anchor = options.initial.u.size() == n ? at(options.initial.u, fixed)
                                                         : Eigen::VectorXd::Zero(static_cast<long>(fixed.size()));

  Timings timings;
  // K⁺ for the certificate: from the solver of K_ε the first step sets up, or (a backend that
  // returns none, as ipopt) from a factorisation of K without F — on a K held whole only; in
  // parts the certificate then has no dual.
  std::shared_ptr<const LinearSolver> K_plus;
  bool looked_for_K_plus = false;
  auto generalised = [&](const SolveResult& step) {
    Stopwatch setting_up;
    looked_for_K_plus = true;
    if (step.K_factor && step.K_factor->ok() && step.K_factor->size() == n)
      K_plus = std::make_shared<GeneralisedInverseOfShifted>(step.K_factor, fixed);
    else if (K.whole)
      K_plus = generalised_inverse(qp.K, fixed, linear_solver_options(qp, options));
    timings.add("generalised_inverse", setting_up.seconds());
  };

  SolveResult result;
  Certificate certificate;
  // As many differences as free modes: more would fit the map's linear model in k dimensions
  // with stale steps of an earlier active set.
  AndersonMixing mixing(std::min<int>(kAndersonMemory, std::max<int>(1, static_cast<int>(R.cols()))));
  int steps = 0, iterations = 0, stalled = 0, softenings = 0;
  double last_change = std::numeric_limits<double>::infinity();
  Eigen::VectorXd last_move;  // the anchors' last move on F
  std::string why;
  while (true) {
    inner.f = qp.f;
    for (size_t j = 0; j < fixed.size(); ++j) inner.f[fixed[j]] += epsilon * anchor[static_cast<long>(j)];
    result = run(inner, inner_options);
    ++steps;
    iterations += result.iterations;
    timings.merge(result.timings);
    if (!looked_for_K_plus) generalised(result);
    certificate = K.certify(result.u, result.lambda, result.lambda_t, K_plus.get());
    if (result.status != Status::Converged) {
      why = "proximal step " + std::to_string(steps) + " ended " + to_string(result.status) + ": " + result.message;
      break;
    }
    if (meets_tolerance(certificate, options.tol)) break;
    const Eigen::VectorXd moved = at(result.u, fixed);
    last_move = moved - anchor;
    const double change = last_move.cwiseAbs().maxCoeff();
    if (!(change > 0)) {
      why = "the proximal steps reached a fixed point whose certificate shows relative KKT residual " +
            short_number(certificate.kkt_max()) + " (the last step: " + result.message + ")";
      break;
    }
    // A free motion the load drives and no row stops moves by f/ε every step: no contraction.
    stalled = change > 0.9 * last_change ? stalled + 1 : 0;
    // A step contracts the error by about ε/(ε + c), c the stiffness with which the contacts
    // hold the motion — small for a body friction holds near gross slip (Q → μP: the stick zone
    // shrinks). There the steps still contract, slowly: softer springs (ε / 10, a new factor of
    // K_ε, up to kProximalSoftenings times) unless the load beyond friction is what moves them.
    Eigen::VectorXd ignored;
    if (stalled >= 3 && softenings < kProximalSoftenings && steps < kProximalMaxSteps &&
        !gross_slip(qp, R, fixed, last_move, result, ignored)) {
      add_springs(-0.9 * epsilon);
      epsilon *= 0.1;
      ++softenings;
      stalled = 0;
      last_change = std::numeric_limits<double>::infinity();
      mixing = AndersonMixing(std::min<int>(kAndersonMemory, std::max<int>(1, static_cast<int>(R.cols()))));
      anchor = moved;
      inner_options.K_factor = nullptr;
      inner_options.initial = {result.u, result.lambda, result.lambda_t};
      continue;
    }
    if (stalled >= 3 || steps >= kProximalMaxSteps) {
      why = "the free modes did not settle in " + std::to_string(steps) + " proximal steps (the last moved " +
            short_number(change) + ")";
      break;
    }
    last_change = change;
    anchor = mixing.next(anchor, moved);
    inner_options.K_factor = result.K_factor;
    inner_options.initial = {result.u, result.lambda, result.lambda_t};
  }

  const std::string inner_message = result.message;
  result.K_factor = K_plus;
  result.iterations = iterations;
  result.certificate = certificate;
  const bool certified = why.empty();
  std::optional<std::string> slip;
  int unseen = 0;
  if (certified) unseen = take_smallest_norm(qp, R, K, K_plus.get(), options.tol, result);
  result.timings = timings;
  result.timings.add("free_modes", clock.seconds());
  result.diagnostics["proximal_steps"] = steps;
  result.diagnostics["free_modes"] = static_cast<double>(R.cols());
  result.diagnostics["rigid_balance"] = rigid_balance(qp, R, K, result);
  if (unseen > 0) result.diagnostics["undriven_modes"] = unseen;
  const std::string modes = std::to_string(R.cols()) + " free mode" + (R.cols() == 1 ? "" : "s") + " of K";
  if (certified) {
    result.status = Status::Converged;
    result.message = "converged: " + modes + " held by the rows, " + std::to_string(steps) +
                     " proximal steps (the last: " + inner_message + ")" +
                     (unseen > 0 ? "; " + std::to_string(unseen) +
                                       " of them no active row sees nor the load drives: u takes the smallest norm "
                                       "along them"
                                 : "");
  } else if (Eigen::VectorXd slide; result.status == Status::Converged && last_move.size() > 0 &&
                                    (slip = gross_slip(qp, R, fixed, last_move, result, slide))) {
    result.status = Status::Unbounded;
    result.recession = slide;
    result.message = *slip;
  } else {
    if (result.status == Status::Converged) result.status = Status::MaxIterations;
    result.message = modes + ": " + why;
  }
  return result;
}

}  // namespace contactqp::detail
