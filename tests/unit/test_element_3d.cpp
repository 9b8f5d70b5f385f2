// 3D element stiffness (4- and 10-node tetrahedra): six rigid-body modes carry no energy, the
// constant-strain patch test, the consistent body force, and the same kernel as 2D for dim = 2.
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

#include "contactqp/model.hpp"
#include "mesh/shape_functions.hpp"
#include "qp/dense_decompositions.hpp"

using namespace contactqp;

namespace {

// A tetrahedron of general shape; for order 2 the mid-edge nodes are moved off the edges (a
// curved isoparametric element whose Jacobian stays positive).
std::vector<Eigen::Vector3d> tetrahedron(int order) {
  std::vector<Eigen::Vector3d> x = {{0.1, 0.2, 0.0}, {1.3, 0.1, 0.2}, {0.4, 1.1, -0.1}, {0.3, 0.4, 1.2}};
  if (order == 2) {
    const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    const Eigen::Vector3d shift[6] = {{0.02, -0.03, 0.01}, {0.03, 0.02, -0.02}, {-0.02, 0.0, 0.03},
                                      {0.01, 0.02, -0.01}, {-0.03, 0.01, 0.02}, {0.0, -0.02, 0.01}};
    for (int k = 0; k < 6; ++k) x.push_back(0.5 * (x[edge[k][0]] + x[edge[k][1]]) + shift[k]);
  }
  return x;
}

// Nodal values of u(x) = a + A x.
Eigen::VectorXd linear_field(const std::vector<Eigen::Vector3d>& x, const Eigen::Vector3d& a,
                             const Eigen::Matrix3d& A) {
  Eigen::VectorXd u(3 * x.size());
  for (size_t i = 0; i < x.size(); ++i) u.segment<3>(3 * i) = a + A * x[i];
  return u;
}

double volume(const std::vector<Eigen::Vector3d>& x) {
  return (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) / 6.0;
}

ElementLaw solid_law(double E, double nu) {
  return element_law(ElasticModel::Solid, {E, nu}, Formulation::Displacement);
}

}  // namespace

TEST_CASE("tetrahedra: six rigid-body modes give zero energy, and K_e has exactly six", "[unit][element][3d]") {
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  const auto x = tetrahedron(order);
  const ElementType type = element_type(3, order);
  const Eigen::MatrixXd Ke = element_stiffness(type, x.data(), solid_law(210e3, 0.3), 1.0);
  REQUIRE(Ke.rows() == 3 * nodes_per_element(type));
  CHECK((Ke - Ke.transpose()).norm() <= 1e-12 * Ke.norm());
  std::vector<Eigen::VectorXd> modes;
  for (int c = 0; c < 3; ++c) modes.push_back(linear_field(x, Eigen::Vector3d::Unit(c), Eigen::Matrix3d::Zero()));
  for (int c = 0; c < 3; ++c) {
    Eigen::Matrix3d W;  // ω × x for ω = e_c
    const Eigen::Vector3d w = Eigen::Vector3d::Unit(c);
    W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    modes.push_back(linear_field(x, Eigen::Vector3d::Zero(), W));
  }
  for (const Eigen::VectorXd& r : modes) CHECK((Ke * r).norm() <= 1e-10 * Ke.norm() * r.norm());
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Ke).eigenvalues();
  const double largest = eigenvalues.maxCoeff();
  int zero = 0;
  for (int i = 0; i < eigenvalues.size(); ++i) {
    CHECK(eigenvalues[i] > -1e-10 * largest);
    if (eigenvalues[i] < 1e-10 * largest) ++zero;
  }
  CHECK(zero == 6);
}

TEST_CASE("tetrahedra: a constant strain gives the exact strain energy", "[unit][element][3d]") {
  // ½ uᵀ K_e u of u = A x is ½ εᵀ D ε · V, with ε the symmetric part of A in Voigt form and D
  // from λ, μ directly (an independent writing of Hooke's law: σ = λ tr ε I + 2 μ ε).
  const int order = GENERATE(1, 2);
  CAPTURE(order);
  auto x = tetrahedron(order);
  if (order == 2) {  // straight edges: the volume is the vertices' tetrahedron's
    const int edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (int k = 0; k < 6; ++k) x[4 + k] = 0.5 * (x[edge[k][0]] + x[edge[k][1]]);
  }
  const double E = 3.0, nu = 0.27;
  const Eigen::MatrixXd Ke = element_stiffness(element_type(3, order), x.data(), solid_law(E, nu), 1.0);
  Eigen::Matrix3d A;
  A << 1e-3, 2e-3, -1e-3, 5e-4, -2e-3, 3e-4, -7e-4, 1e-4, 4e-3;
  const Eigen::VectorXd u =
      linear_field(x, Eigen::Vector3d(1e-3, -2e-3, 3e-3), A);  // a rigid part of the size of the strains
  const Eigen::Matrix3d eps = 0.5 * (A + A.transpose());
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const Eigen::Matrix3d sigma = lambda * eps.trace() * Eigen::Matrix3d::Identity() + 2 * mu * eps;
  const double exact = 0.5 * (sigma.cwiseProduct(eps)).sum() * volume(x);
  CHECK(0.5 * u.dot(Ke * u) == Approx(exact).epsilon(1e-12));
}

TEST_CASE("tetrahedra: the 2D kernel is the dim = 2 case: a triangle's stiffness is unchanged", "[unit][element][3d]") {
  // The same triangle through the 2D convenience form and through the run-time element type.
  const std::vector<Eigen::Vector2d> x2 = {{0.1, 0.2}, {1.3, 0.1}, {0.4, 1.1}};
  std::vector<Eigen::Vector3d> x3;
  for (const auto& p : x2) x3.emplace_back(p.x(), p.y(), 0.0);
  const ElementLaw law = element_law(ElasticModel::PlaneStrain, {2.0, 0.3}, Formulation::Displacement);
  CHECK(element_stiffness(x2.data(), 1, law, 0.5) == element_stiffness(ElementType::Tri3, x3.data(), law, 0.5));
}

TEST_CASE("tetrahedra: the shape functions interpolate and sum to one", "[unit][element][3d]") {
  const int order = GENERATE(1, 2);
  const int n = order == 1 ? 4 : 10;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d at = detail::reference_tetrahedron_node(i);
    const Eigen::VectorXd N = detail::tetrahedron_values(order, at.x(), at.y(), at.z());
    for (int j = 0; j < n; ++j) CHECK(N[j] == Approx(i == j ? 1.0 : 0.0).margin(1e-14));
  }
  // Gradients against central differences at an interior point.
  const double h = 1e-6, p[3] = {0.21, 0.17, 0.33};
  const Eigen::Matrix<double, 3, Eigen::Dynamic> dN = detail::tetrahedron_gradients(order, p[0], p[1], p[2]);
  for (int c = 0; c < 3; ++c) {
    double plus[3] = {p[0], p[1], p[2]}, minus[3] = {p[0], p[1], p[2]};
    plus[c] += h;
    minus[c] -= h;
    const Eigen::VectorXd fd = (detail::tetrahedron_values(order, plus[0], plus[1], plus[2]) -
                                detail::tetrahedron_values(order, minus[0], minus[1], minus[2])) /
                               (2 * h);
    CHECK((fd.transpose() - dN.row(c)).norm() < 1e-8);
    CHECK(dN.row(c).sum() == Approx(0.0).margin(1e-13));
  }
}
