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

namespace {

// The 7-point Laplacian of an n × n × n grid, shifted to be positive definite.
Eigen::SparseMatrix<double> laplacian_3d(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  const auto index = [n](int i, int j, int k) { return (i * n + j) * n + k; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const int row = index(i, j, k);
        entries.emplace_back(row, row, 6.1);
        const int neighbours[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        for (const auto& q : neighbours)
          if (q[0] < n && q[1] < n && q[2] < n) {
            entries.emplace_back(row, index(q[0], q[1], q[2]), -1.0);
            entries.emplace_back(index(q[0], q[1], q[2]), row, -1.0);
          }
      }
  Eigen::SparseMatrix<double> A(n * n * n, n * n * n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace

TEST_CASE("the predicted factor is the one factorising builds, without factorising", "[unit][cholesky]") {
  // A tridiagonal matrix has no fill: nnz(L) = 2n − 1 exactly.
  const FactorPrediction line = CholeskyFactor::predict(laplacian_1d(200, 0.01), Ordering::Amd);
  REQUIRE(line.ok);
  CHECK(line.factor_nonzeros == 399);
  CHECK(line.fits_32bit_indices);
  // On a 3D grid (fill, supernodes), the prediction equals the numeric factor's count, for each
  // ordering, and the bytes cover at least the values.
  const Eigen::SparseMatrix<double> A = laplacian_3d(14);
  for (Ordering ordering : {Ordering::Amd, Ordering::Metis}) {
    const FactorPrediction p = CholeskyFactor::predict(A, ordering);
    const CholeskyFactor factor(A, ordering);
    REQUIRE(p.ok);
    REQUIRE(factor.ok());
    CHECK(p.ordering == factor.ordering_name());
    CHECK(p.supernodal == factor.supernodal());
    CHECK(p.factor_nonzeros == factor.factor_nonzeros());
    CHECK(p.factor_nonzeros > 10 * A.rows());  // the grid fills in
    CHECK(p.factor_bytes >= 8.0 * p.factor_nonzeros);
    CHECK(p.flops > p.factor_nonzeros);
  }
  CHECK_FALSE(CholeskyFactor::predict(Eigen::SparseMatrix<double>(3, 4)).ok);
}
