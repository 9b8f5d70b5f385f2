// The distributed problem (contactqp/petsc/par_qp.hpp): assembled in rank shares, solved and
// certified by the generic steps with K's products summed over the ranks.
#include "contactqp/petsc/par_qp.hpp"

#include "contactqp/errors.hpp"
#include "mpi.hpp"
#include "petsc_backend.hpp"
#include "rank_share.hpp"
#include "solve_steps.hpp"

namespace contactqp {

ParQuadraticProgram assemble_par_qp(Model& model, const RankShare& share) {
  ParQuadraticProgram qp;
  qp.rank = share.rank;
  qp.ranks = share.ranks;
  if (share.ranks <= 1) {
    qp.share = assemble_qp(model);
    return qp;
  }
  if (!share.distributed_row.empty() && static_cast<int>(share.distributed_row.size()) != model.n_free)
    throw InputError("RankShare.distributed_row", "has " + std::to_string(share.distributed_row.size()) +
                                                      " entries for " + std::to_string(model.n_free) + " DOFs");
  // The rows the ranks partition for themselves need one model on every rank.
  if (share.distributed_row.empty()) detail::check_same_model_on_every_rank(model);
  qp.distributed_row =
      share.distributed_row.empty() ? detail::distributed_rows(model, share.ranks) : share.distributed_row;
  if (qp.distributed_row.empty())
    model.warnings.push_back(
        "the mesh could not be partitioned between the MPI ranks (PETSc's MatPartitioning "
        "failed): each rank assembles the elements of a block of DOFs in their own order");
  qp.share = assemble_qp(model, detail::owned_elements(model, share, qp.distributed_row));
  return qp;
}

namespace {

// K u for a share of K (whole on one rank): the ranks' products summed (collective).
VectorXd share_times(const QuadraticProgram& share, int ranks, const VectorXd& u) {
  VectorXd Ku = share.K * u;
  if (ranks > 1) detail::sum_over_ranks(Ku.data(), Ku.size());
  return Ku;
}

Certificate certify_share(const QuadraticProgram& share, int ranks, const VectorXd& u, const VectorXd& lambda,
                          const VectorXd& lambda_t, const LinearSolver* K_factor) {
  if (ranks <= 1) return certify(share, u, lambda, lambda_t, K_factor);
  // Every vector but K u is whole on every rank (T and λ_T too): the terms need no other sum.
  return certify_given_Ku(share, share_times(share, ranks, u), u, lambda, lambda_t, K_factor);
}

// How solve()'s steps apply K held in shares (solve_steps.hpp): `share` this rank's, kept alive
// by the caller. The proximal steps' springs (floating.hpp) join rank 0's share.
detail::KOperations shares_K(const QuadraticProgram& share, int rank, int ranks) {
  detail::KOperations K;
  K.times = [&share, ranks](const VectorXd& u) { return share_times(share, ranks, u); };
  K.diagonal = [&share, ranks]() {
    // A rank's share holds part of each diagonal entry at its boundary: the ranks' sum is K's.
    VectorXd diagonal = share.K.diagonal();
    if (ranks > 1) detail::sum_over_ranks(diagonal.data(), diagonal.size());
    return diagonal;
  };
  K.certify = [&share, ranks](const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                              const LinearSolver* K_factor) {
    return certify_share(share, ranks, u, lambda, lambda_t, K_factor);
  };
  K.whole = ranks <= 1;
  K.like = [rank, ranks](const QuadraticProgram& other) { return shares_K(other, rank, ranks); };
  K.adds_springs = rank == 0;
  return K;
}

}  // namespace

VectorXd K_times(const ParQuadraticProgram& qp, const VectorXd& u) { return share_times(qp.share, qp.ranks, u); }

SolveResult solve(const ParQuadraticProgram& qp, const SolveOptions& options) {
  if (qp.ranks > 1 && options.backend != Backend::Petsc)
    throw InputError("backend",
                     "= " + to_string(options.backend) +
                         ": K is assembled in shares over the MPI ranks, which only the petsc backend solves");
  const detail::MatrixLayout layout{qp.ranks > 1, qp.distributed_row};
  return detail::solve_with(qp.share, options, shares_K(qp.share, qp.rank, qp.ranks),
                            [&layout](const QuadraticProgram& scaled, const SolveOptions& o) {
                              return detail::solve_bound_form(scaled, layout, o);
                            });
}

Certificate certify(const ParQuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda,
                    const LinearSolver* K_factor) {
  return certify(qp, u, lambda, VectorXd(), K_factor);
}

Certificate certify(const ParQuadraticProgram& qp, const VectorXd& u, const VectorXd& lambda, const VectorXd& lambda_t,
                    const LinearSolver* K_factor) {
  return certify_share(qp.share, qp.ranks, u, lambda, lambda_t, K_factor);
}

namespace detail {

std::string petsc_options_of(const std::map<std::string, std::string>& library_options) {
  const auto found = library_options.find("petsc");
  return found == library_options.end() ? std::string() : found->second;
}

}  // namespace detail

std::string petsc_options_of(const SolveOptions& options) { return detail::petsc_options_of(options.library_options); }

void set_petsc_options(SolveOptions& options, const std::string& entries) {
  options.library_options["petsc"] = entries;
}

}  // namespace contactqp
