// The CHOLMOD wrapper against Eigen's own dense Cholesky, and its failure report.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "contactqp/cholesky.hpp"

using namespace contactqp;

namespace {

Eigen::SparseMatrix<double> laplacian_1d(int n, double shift) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0 + shift);
    if (i + 1 < n) {
      entries.emplace_back(i, i + 1, -1.0);
      entries.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace

TEST_CASE("CHOLMOD solves agree with a dense Cholesky, fresh or reused", "[unit][cholesky]") {
  const Eigen::SparseMatrix<double> A = laplacian_1d(200, 0.01);
  const CholeskyFactor factor(A);
  REQUIRE(factor.ok());
  CHECK(factor.failed_column() == -1);
  CHECK(factor.factor_nonzeros() >= 399);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(200, -1.0, 2.0);
  const Eigen::VectorXd exact = Eigen::MatrixXd(A).llt().solve(b);
  const Eigen::VectorXd first = factor.solve(b);
  CHECK((first - exact).norm() <= 1e-12 * exact.norm());
  CHECK((factor.solve(b) - first).norm() == 0.0);  // reuse gives the same bits
  Eigen::MatrixXd several(200, 3);
  several << b, 2 * b, -b;
  const Eigen::MatrixXd X = factor.solve_columns(several);
  CHECK((X.col(1) - 2 * exact).norm() <= 1e-12 * exact.norm());
  // A scaled view divides the solution and shares the factor.
  CHECK((factor.scaled(4.0)->solve(b) - exact / 4.0).norm() <= 1e-12 * exact.norm());
}

TEST_CASE("a matrix that is not positive definite is reported, not solved", "[unit][cholesky]") {
  Eigen::SparseMatrix<double> A = laplacian_1d(50, 0.0);
  A.coeffRef(20, 20) = -1.0;  // indefinite
  const CholeskyFactor factor(A);
  CHECK_FALSE(factor.ok());
  CHECK(factor.message().find("not positive definite") != std::string::npos);
  CHECK(factor.failed_column() >= 0);
  CHECK(factor.solve(Eigen::VectorXd::Ones(50)).allFinite());
}
