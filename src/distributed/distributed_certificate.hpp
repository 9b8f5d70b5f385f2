// The contact QP's solution and certificate on distributed data: from the bound form's v and μ
// back to u = Q v and λ = μ on each rank's own rows, and certificate.hpp's terms (maxima and
// sums over the rows) from each rank's rows of K u, f, Bᵀλ, B u and g, reduced over the ranks, so
// that certificate_from() — the one implementation of the formulas — gives the certificate.
// K is never formed: K u = Tᵀ(A v) at a candidate node (K = Q⁻ᵀ A Q⁻¹, Q⁻¹ = T), A v elsewhere;
// θ's solve with K is one with A: K⁻¹r = Q A⁻¹ Qᵀr.
#pragma once

#include <petscvec.h>

#include <Eigen/Core>
#include <vector>

#include "contactqp/certificate.hpp"
#include "distributed_pdas.hpp"

namespace contactqp::detail {

// This rank's part of the solution in the QP's own variables.
struct DistributedSolution {
  Eigen::VectorXd u;       // the own free DOFs (local free indices 0 … n_own_dofs − 1)
  Eigen::VectorXd lambda;  // the own candidates' rows (candidate order)
};

// u = Q v on the own rows (v in A's layout), λ = μ.
DistributedSolution solution_of(const DistributedModel& model, const DistributedBoundQp& qp, Vec v,
                                const std::vector<double>& mu);

// The terms of this rank's rows, reduced over the ranks (collective); with `solver`, θ's
// rᵀK⁻¹r by one solve with A, to 1e-3 · tol of the certificate's energy scale.
CertificateTerms distributed_certificate_terms(const DistributedModel& model, const DistributedBoundQp& qp,
                                               const DistributedSolution& solution, SolverOfA* solver, double tol);

// The petsc backend's stopping test on distributed data (solvers/petsc.cpp's): primal violation
// / L, negative multipliers / F, complementarity / (F L), without stationarity (the inner solves
// hold it). Collective.
double distributed_kkt_residual(const DistributedModel& model, const DistributedBoundQp& qp, Vec v,
                                const std::vector<double>& mu);

}  // namespace contactqp::detail
