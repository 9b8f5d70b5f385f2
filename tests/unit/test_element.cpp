// Element stiffness: rigid-body modes carry no energy, and the constant-strain patch test;
// the mixed formulation's element (body.formulation "mixed") likewise, and free of locking.
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/model.hpp"
#include "qp/dense_decompositions.hpp"

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
Eigen::VectorXd linear_field(const std::vector<Eigen::Vector2d>& x, const Eigen::Vector2d& a,
                             const Eigen::Matrix2d& A) {
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
                                   linear_field(x, {0, 1}, Eigen::Matrix2d::Zero()), linear_field(x, {0, 0}, rotation)};
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

TEST_CASE("mixed: D splits into a deviatoric part free of λ and the bulk modulus", "[unit][element][mixed]") {
  const Material material{210.0, 0.4999};
  const ElementLaw mixed = element_law(PlaneModel::PlaneStrain, material, Formulation::Mixed);
  const Eigen::Matrix3d D = elasticity_matrix(PlaneModel::PlaneStrain, material);
  const Eigen::Vector3d m(1, 1, 0);
  CHECK((mixed.D + mixed.bulk * m * m.transpose() - D).norm() <= 1e-9 * D.norm());
  const double mu = 210.0 / (2 * 1.4999);
  CHECK(mixed.bulk == Approx(210.0 / (3 * (1 - 2 * 0.4999))));
  CHECK(mixed.D(0, 0) == Approx(4 * mu / 3));
  CHECK(mixed.D(2, 2) == Approx(mu));
}

TEST_CASE("mixed: rigid modes are free, constant strain gives the exact energy", "[unit][element][mixed]") {
  const auto x = triangle(2);
  const ElementLaw law = element_law(PlaneModel::PlaneStrain, {3.0, 0.45}, Formulation::Mixed);
  const Eigen::MatrixXd Ke = element_stiffness(x.data(), 2, law, 1.0);
  CHECK((Ke - Ke.transpose()).norm() <= 1e-12 * Ke.norm());
  Eigen::Matrix2d rotation;
  rotation << 0, -1, 1, 0;
  for (const Eigen::VectorXd& r : {linear_field(x, {1, 0}, Eigen::Matrix2d::Zero()),
                                   linear_field(x, {0, 1}, Eigen::Matrix2d::Zero()), linear_field(x, {0, 0}, rotation)})
    CHECK((Ke * r).norm() <= 1e-10 * Ke.norm() * r.norm());
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ke).eigenvalues();
  int zero = 0;
  for (int i = 0; i < eigenvalues.size(); ++i) {
    CHECK(eigenvalues[i] > -1e-10 * eigenvalues.maxCoeff());
    zero += eigenvalues[i] < 1e-10 * eigenvalues.maxCoeff();
  }
  CHECK(zero == 3);

  // Straight sides: u = A x has constant strain, so the mean of tr ε is tr ε and the two
  // formulations store the same energy.
  auto straight = x;
  for (int k = 0; k < 3; ++k) straight[3 + k] = 0.5 * (straight[k] + straight[(k + 1) % 3]);
  Eigen::Matrix2d A;
  A << 0.01, 0.003, -0.002, -0.02;
  const Eigen::VectorXd u = linear_field(straight, {0.1, -0.2}, A);
  const Eigen::MatrixXd K_mixed = element_stiffness(straight.data(), 2, law, 0.7);
  const Eigen::MatrixXd K_displacement =
      element_stiffness(straight.data(), 2, elasticity_matrix(PlaneModel::PlaneStrain, {3.0, 0.45}), 0.7);
  CHECK(u.dot(K_mixed * u) == Approx(u.dot(K_displacement * u)).epsilon(1e-12));
  CHECK(element_mean_dilatation(straight.data(), 2, u) == Approx(A(0, 0) + A(1, 1)).epsilon(1e-12));
}

TEST_CASE("mixed: a deformation of zero mean dilatation costs the same whatever ν", "[unit][element][mixed]") {
  // u = ((x − x_c)², 0) on a straight 6-node triangle (x_c its centroid): tr ε = 2(x − x_c)
  // changes volume locally but not on average. The displacement formulation charges
  // λ ∫ (tr ε)², which grows without bound as ν → 0.5 — locking; the mixed one sees only the
  // element mean, zero, so the energy stays that of the shear modulus.
  auto x = triangle(2);
  for (int k = 0; k < 3; ++k) x[3 + k] = 0.5 * (x[k] + x[(k + 1) % 3]);
  const double xc = (x[0].x() + x[1].x() + x[2].x()) / 3;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(12);
  for (int i = 0; i < 6; ++i) u[2 * i] = (x[i].x() - xc) * (x[i].x() - xc);
  CHECK(element_mean_dilatation(x.data(), 2, u) == Approx(0.0).margin(1e-14));
  double mixed_first = -1, displacement_first = -1;
  for (double nu : {0.3, 0.49, 0.4999, 0.499999}) {
    CAPTURE(nu);
    const Material material{2 * (1 + nu), nu};  // μ = 1 throughout
    const double mixed = u.dot(
        element_stiffness(x.data(), 2, element_law(PlaneModel::PlaneStrain, material, Formulation::Mixed), 1.0) * u);
    const double displacement =
        u.dot(element_stiffness(x.data(), 2, elasticity_matrix(PlaneModel::PlaneStrain, material), 1.0) * u);
    if (mixed_first < 0) {
      mixed_first = mixed;
      displacement_first = displacement;
    }
    CHECK(mixed == Approx(mixed_first).epsilon(1e-9));
    if (nu > 0.49999) CHECK(displacement > 1e3 * displacement_first);  // λ = 5e5 μ: locked
  }
}
