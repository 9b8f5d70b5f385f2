// Element stiffness: rigid-body modes carry no energy, and the constant-strain patch test.
#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/model.hpp"

using namespace contactqp;

namespace {

// A curved 6-node triangle (mid-side nodes moved off the chords) and a straight 3-node one.
std::vector<Eigen::Vector2d> triangle(int order) {
  std::vector<Eigen::Vector2d> x = {{0.1, 0.2}, {1.3, 0.1}, {0.4, 1.1}};
  if (order == 2) {
    x.push_back(0.5 * (x[0] + x[1]) + Eigen::Vector2d(0.02, -0.05));
    x.push_back(0.5 * (x[1] + x[2]) + Eigen::Vector2d(0.06, 0.03));
    x.push_back(0.5 * (x[2] + x[0]) + Eigen::Vector2d(-0.04, 0.0));
  }
  return x;
}

// Nodal values of a displacement field u(x) = a + A x.
Eigen::VectorXd linear_field(const std::vector<Eigen::Vector2d>& x, const Eigen::Vector2d& a, const Eigen::Matrix2d& A) {
  Eigen::VectorXd u(2 * x.size());
  for (size_t i = 0; i < x.size(); ++i) u.segment<2>(2 * i) = a + A * x[i];
  return u;
}

}  // namespace

TEST_CASE("rigid-body modes give zero energy and K_e has exactly three of them", "[unit][element]") {
  const int order = GENERATE(1, 2);
  const PlaneModel model = GENERATE(PlaneModel::PlaneStrain, PlaneModel::PlaneStress);
  CAPTURE(order, to_string(model));
  const auto x = triangle(order);
  const Eigen::Matrix3d D = elasticity_matrix(model, {210e3, 0.3});
  const Eigen::MatrixXd Ke = element_stiffness(x.data(), order, D, 1.0);
  CHECK((Ke - Ke.transpose()).norm() <= 1e-12 * Ke.norm());

  Eigen::Matrix2d rotation;
  rotation << 0, -1, 1, 0;
  const Eigen::VectorXd modes[] = {linear_field(x, {1, 0}, Eigen::Matrix2d::Zero()),
                                   linear_field(x, {0, 1}, Eigen::Matrix2d::Zero()),
                                   linear_field(x, {0, 0}, rotation)};
  for (const Eigen::VectorXd& r : modes) CHECK((Ke * r).norm() <= 1e-10 * Ke.norm() * r.norm());

  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ke).eigenvalues();
  const double largest = eigenvalues.maxCoeff();
  int zero = 0;
  for (int i = 0; i < eigenvalues.size(); ++i) {
    CHECK(eigenvalues[i] > -1e-10 * largest);
    if (eigenvalues[i] < 1e-10 * largest) ++zero;
  }
  CHECK(zero == 3);
}

TEST_CASE("a constant strain gives the exact strain energy", "[unit][element]") {
  // Energy ½ uᵀ K_e u of u = A x equals ½ εᵀ D ε · area · thickness for every element shape.
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  auto x = triangle(order);
  if (order == 2)  // straight sides, so that the area is the vertex triangle's
    for (int k = 0; k < 3; ++k) x[3 + k] = 0.5 * (x[k] + x[(k + 1) % 3]);
  const Eigen::Matrix3d D = elasticity_matrix(PlaneModel::PlaneStrain, {1.0, 0.25});
  const double thickness = 0.7;
  const Eigen::MatrixXd Ke = element_stiffness(x.data(), order, D, thickness);
  Eigen::Matrix2d A;
  A << 0.01, 0.003, -0.002, -0.02;
  const Eigen::VectorXd u = linear_field(x, {0.1, -0.2}, A);
  const Eigen::Vector3d strain(A(0, 0), A(1, 1), A(0, 1) + A(1, 0));
  const double area = 0.5 * std::abs((x[1] - x[0]).x() * (x[2] - x[0]).y() - (x[1] - x[0]).y() * (x[2] - x[0]).x());
  const double exact = 0.5 * strain.dot(D * strain) * area * thickness;
  CHECK(0.5 * u.dot(Ke * u) == Approx(exact).epsilon(1e-12));
}

TEST_CASE("plane-strain and plane-stress elasticity matrices", "[unit][element]") {
  const Material steel{200.0, 0.3};
  const Eigen::Matrix3d strain = elasticity_matrix(PlaneModel::PlaneStrain, steel);
  const Eigen::Matrix3d stress = elasticity_matrix(PlaneModel::PlaneStress, steel);
  // Uniaxial stress in plane stress: σxx = E εxx when εyy = −ν εxx.
  CHECK((stress * Eigen::Vector3d(1, -0.3, 0))[0] == Approx(200.0));
  CHECK((stress * Eigen::Vector3d(1, -0.3, 0))[1] == Approx(0.0).margin(1e-12));
  // Shear modulus G = E / (2(1 + ν)) in both.
  CHECK(strain(2, 2) == Approx(200.0 / 2.6));
  CHECK(stress(2, 2) == Approx(200.0 / 2.6));
  // Plane strain, uniaxial strain: σxx = E(1 − ν)/((1 + ν)(1 − 2ν)) εxx.
  CHECK(strain(0, 0) == Approx(200.0 * 0.7 / (1.3 * 0.4)));
}
