// The status never claims more than the certificate shows, and a QP without solution says so
// with its evidence: small QPs whose answers are known by hand (floating chains of springs pushed
// against walls and pulled away from them, a free point in a corner, rows that contradict each
// other, a stiffness contrast, a grounding spring 1e12 times weaker than the chain) on every
// backend. docs/extremes.md, "What converged means" and "Problems without a solution".
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/backend.hpp"
#include "contactqp/certificate.hpp"
#include "contactqp/solve.hpp"
#include "test_support.hpp"

using namespace contactqp;
using namespace contactqp::testing;

namespace {

// A wall to the right of mass j at `gap` (u_j ≤ gap) or to its left (−u_j ≤ gap).
Eigen::RowVectorXd wall_row(int n, int j, double side) {
  Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
  row(j) = side;
  return row;
}

struct StatusCase {
  const char* name;
  QuadraticProgram qp;
  Status expected;         // Converged when the QP has a solution, else Infeasible or Unbounded
  Eigen::VectorXd u, lam;  // the solution known by hand, when unique in u
};

std::vector<StatusCase> status_battery() {
  std::vector<StatusCase> cases;
  {
    // Three masses, springs 1 and 2, pushed right by 1 at mass 0 against a wall 0.5 right of
    // mass 2, a wall 2 left of mass 0 untouched: every spring carries 1 in compression, so
    // u = (0.5 + 1/2 + 1/1, 0.5 + 1/2, 0.5) and λ = (0, 1).
    Eigen::MatrixXd B(2, 3);
    B << wall_row(3, 0, -1), wall_row(3, 2, 1);
    const Eigen::Vector3d f(1, 0, 0);
    cases.push_back({"floating chain pushed against a wall",
                     make_qp(chain_of_springs({1, 2}), f, B, Eigen::Vector2d(2, 0.5)), Status::Converged,
                     Eigen::Vector3d(2, 1, 0.5), Eigen::Vector2d(0, 1)});
  }
  {
    // The same chain pulled left, with only the right wall: nothing stops it.
    Eigen::MatrixXd B = wall_row(3, 2, 1);
    cases.push_back({"floating chain pulled away from its wall",
                     make_qp(chain_of_springs({1, 2}), Eigen::Vector3d(-1, 0, 0), B, Eigen::VectorXd::Constant(1, 0.5)),
                     Status::Unbounded,
                     {},
                     {}});
  }
  {
    // Pulled apart by 1 at each end between walls 0.25 beyond them: free, the chain would stretch
    // 1.5 (springs 1 and 2 in series); the walls allow 0.5, so the tension is 0.5/1.5 and the
    // walls carry the rest of each end's load.
    Eigen::MatrixXd B(2, 3);
    B << wall_row(3, 0, -1), wall_row(3, 2, 1);
    const double tension = 0.5 / 1.5;
    cases.push_back({"floating chain pulled apart against two walls",
                     make_qp(chain_of_springs({1, 2}), Eigen::Vector3d(-1, 0, 1), B, Eigen::Vector2d(0.25, 0.25)),
                     Status::Converged, Eigen::Vector3d(-0.25, -0.25 + tension / 1, 0.25),
                     Eigen::Vector2d(1 - tension, 1 - tension)});
  }
  {
    // A free point (K = 0) pushed by (−1, −2) into the corner of two walls at x ≥ 0, y ≥ 0.
    Eigen::MatrixXd B(2, 2);
    B << -1, 0, 0, -1;
    cases.push_back({"free point pushed into a corner",
                     make_qp(Eigen::MatrixXd::Zero(2, 2), Eigen::Vector2d(-1, -2), B, Eigen::Vector2d::Zero()),
                     Status::Converged, Eigen::Vector2d::Zero(), Eigen::Vector2d(1, 2)});
  }
  {
    // The free point pushed along the wall x ≥ 0: the wall cannot stop a motion along it.
    Eigen::MatrixXd B(1, 2);
    B << -1, 0;
    cases.push_back({"free point pushed along its wall",
                     make_qp(Eigen::MatrixXd::Zero(2, 2), Eigen::Vector2d(-1, 1), B, Eigen::VectorXd::Zero(1)),
                     Status::Unbounded,
                     {},
                     {}});
  }
  {
    // u0 ≤ −1 and u0 ≥ 1: no u satisfies both, whatever K.
    Eigen::MatrixXd B(2, 2);
    B << 1, 0, -1, 0;
    cases.push_back({"contradictory rows",
                     make_qp(chain_of_springs({1}, 1), Eigen::Vector2d(0.3, 0), B, Eigen::Vector2d(-1, -1)),
                     Status::Infeasible,
                     {},
                     {}});
  }
  {
    // Stiffness contrast 1e4, grounded at mass 0 by 1, pushed at mass 2 by 1e4 toward a wall 0.5
    // away: the free answer (1e4 + 1 + 1e-4 ...) passes the wall, which carries the rest.
    const Eigen::MatrixXd K = chain_of_springs({1e4, 1}, 1);
    Eigen::MatrixXd B = wall_row(3, 2, 1);
    const Eigen::Vector3d f(0, 0, 1e4);
    // At the wall u2 = 0.5: masses 0 and 1 are a grounded spring 1 in series with 1e4.
    const double series = 1.0 / (1.0 + 1.0 / 1e4);  // springs ground (1) and 1e4 in series
    // Spring 1 between masses 1 and 2, then that series stiffness to the ground.
    const double total = 1.0 / (1.0 / 1 + 1.0 / series);  // mass 2 to the ground
    const double force = total * 0.5;                     // what the chain carries at u2 = 0.5
    const double u0 = force / 1.0, u1 = u0 + force / 1e4;
    cases.push_back({"stiffness contrast 1e4", make_qp(K, f, B, Eigen::VectorXd::Constant(1, 0.5)), Status::Converged,
                     Eigen::Vector3d(u0, u1, 0.5), Eigen::VectorXd::Constant(1, 1e4 - force)});
  }
  {
    // A grounding spring 1e-12 of the chain's: pulled away from its wall, the answer would be
    // 1e12 long. Below kNullRelative the grounding counts as none: unbounded.
    Eigen::MatrixXd B = wall_row(3, 2, 1);
    cases.push_back(
        {"chain grounded by 1e-12, pulled away",
         make_qp(chain_of_springs({1, 1}, 1e-12), Eigen::Vector3d(-1, 0, 0), B, Eigen::VectorXd::Constant(1, 0.5)),
         Status::Unbounded,
         {},
         {}});
  }
  return cases;
}

}  // namespace

TEST_CASE("the hand-made answers of the status battery are KKT points", "[status]") {
  // The battery's own truth, checked independently of every backend.
  for (const StatusCase& c : status_battery()) {
    if (c.expected != Status::Converged) continue;
    INFO(c.name);
    const Certificate certificate = certify(c.qp, c.u, c.lam);
    CHECK(certificate.kkt_max() < 1e-12);
  }
}

TEST_CASE("no backend's status claims more than the certificate shows", "[status][cross_backend]") {
  const double tol = 1e-8;
  for (const StatusCase& c : status_battery()) {
    for (const Backend backend : available_backends(c.qp)) {
      INFO(c.name << " on " << to_string(backend));
      SolveOptions options;
      options.backend = backend;
      options.tol = tol;
      const SolveResult r = solve(c.qp, options);
      INFO(r.message);
      REQUIRE(r.certificate.has_value());
      // The stored certificate is the one anyone computes for (u, λ).
      const Certificate again = certify(c.qp, r.u, r.lambda);
      CHECK(again.kkt_max() == Approx(r.certificate->kkt_max()).margin(1e-14));
      CHECK(r.u.allFinite());
      CHECK(r.u.cwiseAbs().maxCoeff() < 1e10);
      if (r.status == Status::Converged) {
        CHECK(meets_tolerance(*r.certificate, tol));
        CHECK(c.expected == Status::Converged);
        if (c.u.size() > 0) {
          CHECK((r.u - c.u).cwiseAbs().maxCoeff() <= 1e-5 * std::max(1.0, c.u.cwiseAbs().maxCoeff()));
          CHECK((r.lambda - c.lam).cwiseAbs().maxCoeff() <= 1e-5 * std::max(1.0, c.lam.cwiseAbs().maxCoeff()));
        }
      }
      if (c.expected == Status::Infeasible) {
        CHECK(r.status == Status::Infeasible);
        REQUIRE(r.farkas.size() == c.qp.n_constraints());
        CHECK(r.farkas.minCoeff() >= 0);
        CHECK(c.qp.g.dot(r.farkas) < 0);
        CHECK((c.qp.B.transpose() * r.farkas).cwiseAbs().maxCoeff() < 1e-12);
      }
      if (c.expected == Status::Unbounded) {
        CHECK(r.status == Status::Unbounded);
        REQUIRE(r.recession.size() == c.qp.n_dofs());
        CHECK(c.qp.f.dot(r.recession) > 0);
        CHECK((c.qp.B * r.recession).maxCoeff() <= 1e-12);
        CHECK((c.qp.K * r.recession).cwiseAbs().maxCoeff() <= 1e-9 * c.qp.K.cwiseAbs().sum());
      }
    }
  }
}

TEST_CASE("a backend's converged is overruled when the certificate exceeds tol", "[status]") {
  // uzawa stopped after 3 iterations claims nothing; certified_status keeps a non-converged
  // status as it is, and overrules a converged claim the certificate does not back.
  Certificate good, bad;
  bad.stationarity = 1e-5;
  CHECK(certified_status(good, 1e-8, Status::Converged) == Status::Converged);
  CHECK(certified_status(bad, 1e-8, Status::Converged) == Status::Inaccurate);
  CHECK(certified_status(bad, 1e-8, Status::MaxIterations) == Status::MaxIterations);
  Certificate gap;
  gap.relative_gap = -5e-7;  // a gap of either sign beyond 10 × tol
  CHECK(certified_status(gap, 1e-8, Status::Converged) == Status::Inaccurate);
  gap.dual_available = false;  // no θ: the KKT residual alone decides
  CHECK(certified_status(gap, 1e-8, Status::Converged) == Status::Converged);
}
