// solution_of(), distributed_certificate_terms() and distributed_kkt_residual()
// (distributed_certificate.hpp).
#include "distributed_certificate.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact/contact.hpp"
#include "petsc/ksp_helpers.hpp"
#include "petsc/petsc_runtime.hpp"

namespace contactqp::detail {
namespace {

// x_C = M x_C at every own candidate node (M = T, Q, Tᵀ or Qᵀ of its transform).
template <class Pick>
void per_node(const DistributedModel& model, const DistributedBoundQp& qp, double* x, Pick pick) {
  for (const NodeTransform& t : qp.transforms) {
    if (t.node >= model.n_owned) continue;
    Eigen::VectorXd part(t.columns.size());
    for (std::size_t a = 0; a < t.columns.size(); ++a) part[a] = x[t.columns[a]];
    part = pick(t) * part;
    for (std::size_t a = 0; a < t.columns.size(); ++a) x[t.columns[a]] = part[a];
  }
}

// Free-DOF values (own free DOFs, local free order) into and out of a vector in A's rows
// (the prescribed DOFs' rows 0).
void to_rows(const DistributedModel& model, const Eigen::VectorXd& free, Vec rows) {
  VecSet(rows, 0.0);
  PetscScalar* values = nullptr;
  VecGetArray(rows, &values);
  for (int k = 0; k < model.n_own_dofs; ++k) values[model.local_row(k)] = free[k];
  VecRestoreArray(rows, &values);
}

Eigen::VectorXd from_rows(const DistributedModel& model, Vec rows) {
  Eigen::VectorXd free(model.n_own_dofs);
  const PetscScalar* values = nullptr;
  VecGetArrayRead(rows, &values);
  for (int k = 0; k < model.n_own_dofs; ++k) free[k] = values[model.local_row(k)];
  VecRestoreArrayRead(rows, &values);
  return free;
}

// K u on the own rows from u: Tᵀ A T u (A v, with v = T u at the candidate nodes).
Eigen::VectorXd K_times_u(const DistributedModel& model, const DistributedBoundQp& qp, const Eigen::VectorXd& u) {
  Vec v = nullptr, y = nullptr;
  check_petsc(MatCreateVecs(qp.A, &v, &y), "MatCreateVecs");
  Eigen::VectorXd Tu = u;
  per_node(model, qp, Tu.data(), [](const NodeTransform& t) -> const Eigen::MatrixXd& { return t.T; });
  to_rows(model, Tu, v);
  const PetscErrorCode code = MatMult(qp.A, v, y);
  Eigen::VectorXd Ku = code ? Eigen::VectorXd::Zero(u.size()) : from_rows(model, y);
  per_node(model, qp, Ku.data(), [](const NodeTransform& t) { return Eigen::MatrixXd(t.T.transpose()); });
  VecDestroy(&v);
  VecDestroy(&y);
  check_petsc(code, "MatMult");
  return Ku;
}

// This rank's terms (not yet reduced): λ gives Bᵀλ and the complementarity, `mu` the negative part.
CertificateTerms row_terms(const DistributedModel& model, const DistributedBoundQp& qp, const Eigen::VectorXd& u,
                           const Eigen::VectorXd& Ku, const Eigen::VectorXd& lambda, const Eigen::VectorXd& mu,
                           Eigen::VectorXd* stationarity) {
  const Model& local = model.local;
  CertificateTerms t;
  const Eigen::VectorXd f = from_rows(model, qp.f);
  Eigen::VectorXd Btl = Eigen::VectorXd::Zero(u.size());
  for (int i = 0; i < model.n_own_candidates; ++i) {
    const ContactRowEntries row = contact_row(local, local.candidates[i]);
    double Bu = 0;
    for (const auto& [column, value] : row.coefficients) {
      Bu += value * u[column];
      Btl[column] += value * lambda[i];
    }
    const double slack = Bu - row.g;
    t.Bu_max = std::max(t.Bu_max, std::abs(Bu));
    t.violation_max = std::max(t.violation_max, slack);
    t.complementarity_max = std::max(t.complementarity_max, std::abs(lambda[i] * slack));
    t.lambda_slack += lambda[i] * slack;
    t.lambda_max = std::max(t.lambda_max, std::abs(lambda[i]));
    t.negative_max = std::max(t.negative_max, -mu[i]);
  }
  if (stationarity) stationarity->resize(u.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const double r = Ku[k] - f[k] + Btl[k];
    if (stationarity) (*stationarity)[k] = r;
    t.f_max = std::max(t.f_max, std::abs(f[k]));
    t.Ku_max = std::max(t.Ku_max, std::abs(Ku[k]));
    t.Btl_max = std::max(t.Btl_max, std::abs(Btl[k]));
    t.u_max = std::max(t.u_max, std::abs(u[k]));
    t.stationarity_max = std::max(t.stationarity_max, std::abs(r));
    t.uKu += u[k] * Ku[k];
    t.fu += f[k] * u[k];
  }
  return t;
}

// Maxima and sums over the ranks.
void reduce(CertificateTerms& t) {
  double maxima[10] = {t.f_max,         t.Ku_max,
                       t.Btl_max,       t.u_max,
                       t.Bu_max,        t.stationarity_max,
                       t.violation_max, t.negative_max,
                       t.lambda_max,    t.complementarity_max};
  double sums[3] = {t.uKu, t.fu, t.lambda_slack};
  MPI_Allreduce(MPI_IN_PLACE, maxima, 10, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  t.f_max = maxima[0], t.Ku_max = maxima[1], t.Btl_max = maxima[2], t.u_max = maxima[3], t.Bu_max = maxima[4];
  t.stationarity_max = maxima[5], t.violation_max = maxima[6], t.negative_max = maxima[7];
  t.lambda_max = maxima[8], t.complementarity_max = maxima[9];
  t.uKu = sums[0], t.fu = sums[1], t.lambda_slack = sums[2];
}

Eigen::VectorXd as_vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

DistributedSolution solution_of(const DistributedModel& model, const DistributedBoundQp& qp, Vec v,
                                const std::vector<double>& mu) {
  DistributedSolution out;
  out.u = from_rows(model, v);
  per_node(model, qp, out.u.data(), [](const NodeTransform& t) -> const Eigen::MatrixXd& { return t.Q; });
  out.lambda = as_vector(mu);
  return out;
}

CertificateTerms distributed_certificate_terms(const DistributedModel& model, const DistributedBoundQp& qp,
                                               const DistributedSolution& solution, SolverOfA* solver, double tol) {
  const Eigen::VectorXd Ku = K_times_u(model, qp, solution.u);
  Eigen::VectorXd r;
  CertificateTerms terms = row_terms(model, qp, solution.u, Ku, solution.lambda, solution.lambda, &r);
  reduce(terms);
  if (!solver) return terms;
  // rᵀK⁻¹r = (Qᵀr)ᵀ A⁻¹ (Qᵀr).
  per_node(model, qp, r.data(), [](const NodeTransform& t) { return Eigen::MatrixXd(t.Q.transpose()); });
  Vec rhs = nullptr, y = nullptr;
  check_petsc(MatCreateVecs(qp.A, &y, &rhs), "MatCreateVecs");
  to_rows(model, r, rhs);
  PetscReal force = 0, dot = 0;
  VecNorm(rhs, NORM_INFINITY, &force);
  bool solved = true;
  if (force > 0) {
    // The gap is J − θ(λ) with θ(λ) = L(u, λ) − ½ rᵀK⁻¹r, and certificate_from() measures it
    // against the energy scale below: rᵀK⁻¹r to kInnerFraction · tol of that scale leaves the
    // relative gap right to 1e-3 of tol (SolverOfA::energy says how CG knows).
    const double J = 0.5 * terms.uKu - terms.fu;
    const double energy =
        std::max({std::abs(J), std::abs(J + terms.lambda_slack), 0.5 * std::abs(terms.uKu), std::abs(terms.fu)});
    solved = solver->energy(rhs, y, force, kInnerFraction * tol * energy, &dot);
  }
  VecDestroy(&rhs);
  VecDestroy(&y);
  int all = solved;
  MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (all) terms.r_K_inverse_r = dot;
  return terms;
}

double distributed_kkt_residual(const DistributedModel& model, const DistributedBoundQp& qp, Vec v,
                                const std::vector<double>& mu) {
  const DistributedSolution solution = solution_of(model, qp, v, mu);
  const Eigen::VectorXd Ku = K_times_u(model, qp, solution.u);
  const Eigen::VectorXd raw = as_vector(mu);
  CertificateTerms t = row_terms(model, qp, solution.u, Ku, raw.cwiseMax(0.0), raw, nullptr);
  reduce(t);
  const double F = std::max({t.f_max, t.Ku_max, t.Btl_max}), L = std::max(t.u_max, t.Bu_max);
  auto ratio = [](double x, double scale) { return scale > 0 ? x / scale : x; };
  return std::max({ratio(t.violation_max, L), ratio(t.negative_max, F), ratio(t.complementarity_max, F * L)});
}

}  // namespace contactqp::detail
