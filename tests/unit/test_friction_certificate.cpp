// The friction certificate (certificate.hpp): zero at a known solution, and each of its
// tangential measures catches the mistake it is there for.
#include <catch2/catch.hpp>

#include "contactqp/certificate.hpp"
#include "contactqp/cholesky.hpp"
#include "friction_qps.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

TEST_CASE("the friction certificate is zero at a known solution, 2D and 3D", "[unit][friction]") {
  const FrictionLaw law = GENERATE(FrictionLaw::Tresca, FrictionLaw::Coulomb);
  const int n_directions = GENERATE(1, 2);
  const KnownFrictionQp known = known_friction_qp(8, n_directions, law, 5);
  const FrictionSolution& x = known.exact;
  const Certificate c = certify(known.qp, x.u, x.lambda, x.lambda_t);
  CHECK(c.kkt_max() < 1e-13);
  CHECK(std::abs(c.relative_gap) < 1e-13);
  CHECK(c.dual_available);
}

TEST_CASE("the friction certificate sees a wrong tangential force, a slip where it sticks, and a gap",
          "[unit][friction]") {
  const KnownFrictionQp known = known_friction_qp(8, 2, FrictionLaw::Tresca, 5);
  const FrictionSolution& x = known.exact;
  // Node 1 slips with λ_T on the rim along the slip: reversing λ_T breaks the natural map
  // (and stationarity, which is not what this checks: u is recomputed for it).
  Eigen::VectorXd lambda_t = x.lambda_t;
  lambda_t.segment(2, 2) *= -1;
  // (At the solution the certificate is below 1e-13, the test above.)
  Certificate c = certify(known.qp, x.u, x.lambda, lambda_t);
  CHECK(c.tangential > 1e-3);
  // Outside the disc.
  lambda_t = x.lambda_t;
  lambda_t.segment(0, 2) *= 3.0;
  c = certify(known.qp, x.u, x.lambda, lambda_t);
  CHECK(c.tangential > 1e-3);
  // Without λ_T the stationarity residual shows the missing friction force.
  c = certify(known.qp, x.u, x.lambda);
  CHECK(c.stationarity > 1e-3);
  // A feasible but wrong u: the Tresca gap is positive.
  Eigen::VectorXd u = x.u;
  u[0] += 0.01;  // node 0's tangential DOF: slip at a sticking node costs energy
  c = certify(known.qp, u, x.lambda, x.lambda_t);
  CHECK(c.relative_gap > 1e-6);
  CHECK(c.tangential > 1e-4);
}

TEST_CASE("without friction the certificate is today's", "[unit][friction]") {
  const QuadraticProgram qp = random_qp(6, 4, 3);
  const ExactSolution x = solve_by_enumeration(qp);
  const Certificate a = certify(qp, x.u, x.lambda);
  const Certificate b = certify(qp, x.u, x.lambda, Eigen::VectorXd());
  CHECK(a.stationarity == b.stationarity);
  CHECK(a.duality_gap == b.duality_gap);
  CHECK(b.tangential == 0);
}

// K held in shares (the problem in parts under mpirun: each rank's qp.K a share, K u summed
// over the ranks): certify_given_Ku() with the summed K u is the whole problem's certificate,
// and it never reads the share's K.
TEST_CASE("the friction certificate with K u given is the whole certificate, K held in shares", "[unit][friction]") {
  const FrictionLaw law = GENERATE(FrictionLaw::Tresca, FrictionLaw::Coulomb);
  const int n_directions = GENERATE(1, 2);
  const KnownFrictionQp known = known_friction_qp(8, n_directions, law, 5);
  const FrictionSolution& x = known.exact;
  QuadraticProgram share = known.qp;
  share.K = 0.3 * known.qp.K;  // one rank's share; the other holds 0.7 K
  const Eigen::VectorXd Ku = known.qp.K * x.u;
  const CholeskyFactor factor(known.qp.K);
  // At the answer, and with λ_T left out (the friction force missing from stationarity).
  for (const Eigen::VectorXd& lambda_t : {x.lambda_t, Eigen::VectorXd(Eigen::VectorXd::Zero(x.lambda_t.size()))}) {
    const Certificate whole = certify(known.qp, x.u, x.lambda, lambda_t, &factor);
    const Certificate given = certify_given_Ku(share, Ku, x.u, x.lambda, lambda_t, &factor);
    CHECK(given.stationarity == Approx(whole.stationarity).margin(1e-15));
    CHECK(given.tangential == Approx(whole.tangential).margin(1e-15));
    CHECK(given.complementarity == Approx(whole.complementarity).margin(1e-15));
    CHECK(given.objective == Approx(whole.objective).epsilon(1e-12));
    CHECK(given.relative_gap == Approx(whole.relative_gap).margin(1e-12));
    CHECK(given.dual_available);
  }
  CHECK(certify_given_Ku(share, Ku, x.u, x.lambda, x.lambda_t, &factor).kkt_max() < 1e-13);
  CHECK(certify_given_Ku(share, Ku, x.u, x.lambda, Eigen::VectorXd(), &factor).stationarity > 1e-3);
  // Without a solver of the whole K the dual is not available; the KKT terms are unchanged.
  const Certificate no_dual = certify_given_Ku(share, Ku, x.u, x.lambda, x.lambda_t, nullptr);
  CHECK_FALSE(no_dual.dual_available);
  CHECK(no_dual.kkt_max() < 1e-13);
}
