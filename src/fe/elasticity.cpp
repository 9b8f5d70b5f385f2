// Linear elasticity on 3-node and 6-node triangles (isoparametric), in the displacement
// formulation and in the mixed (P2–P0, condensed) one for nearly incompressible plane strain.
#include <Eigen/LU>
#include <cmath>

#include "contactqp/model.hpp"
#include "shape_functions.hpp"

namespace contactqp {
namespace {

// The strain-displacement matrix at (ξ, η): ε = [εxx, εyy, 2εxy] = Bm · ue; and |det J|.
struct StrainPoint {
  Eigen::Matrix<double, 3, Eigen::Dynamic> Bm;
  double detJ = 0;
};

StrainPoint strain_point(const Eigen::Matrix<double, 2, Eigen::Dynamic>& X, int order, double xi, double eta) {
  const int npe = static_cast<int>(X.cols());
  const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = detail::shape_gradients(order, xi, eta);
  const Eigen::Matrix2d J = dN * X.transpose();  // J(r, c) = d x_c / d ξ_r
  const Eigen::Matrix<double, 2, Eigen::Dynamic> dNdx = J.inverse() * dN;  // rows d/dx, d/dy
  StrainPoint p;
  p.detJ = std::abs(J.determinant());
  p.Bm = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, 2 * npe);
  for (int i = 0; i < npe; ++i) {
    p.Bm(0, 2 * i) = dNdx(0, i);
    p.Bm(1, 2 * i + 1) = dNdx(1, i);
    p.Bm(2, 2 * i) = dNdx(1, i);
    p.Bm(2, 2 * i + 1) = dNdx(0, i);
  }
  return p;
}

Eigen::Matrix<double, 2, Eigen::Dynamic> coordinates(const Eigen::Vector2d* nodes, int order) {
  const int npe = order == 1 ? 3 : 6;
  Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe);
  for (int i = 0; i < npe; ++i) X.col(i) = nodes[i];
  return X;
}

// ∫_T (row of tr ε) dA = ∫ mᵀ Bm dA, and |T|.
void dilatation_row(const Eigen::Matrix<double, 2, Eigen::Dynamic>& X, int order, Eigen::RowVectorXd& row, double& area) {
  const detail::QuadraturePoint* rule = nullptr;
  const int n_points = detail::triangle_rule(order, rule);
  row = Eigen::RowVectorXd::Zero(2 * X.cols());
  area = 0;
  for (int k = 0; k < n_points; ++k) {
    const StrainPoint p = strain_point(X, order, rule[k].xi, rule[k].eta);
    row += (rule[k].weight * p.detJ) * (p.Bm.row(0) + p.Bm.row(1));
    area += rule[k].weight * p.detJ;
  }
}

}  // namespace

Eigen::Matrix3d elasticity_matrix(PlaneModel model, const Material& material) {
  const double E = material.E, nu = material.nu;
  Eigen::Matrix3d D;
  if (model == PlaneModel::PlaneStrain) {
    const double c = E / ((1 + nu) * (1 - 2 * nu));
    D << c * (1 - nu), c * nu, 0,
         c * nu, c * (1 - nu), 0,
         0, 0, c * (1 - 2 * nu) / 2;
  } else {
    const double c = E / (1 - nu * nu);
    D << c, c * nu, 0,
         c * nu, c, 0,
         0, 0, c * (1 - nu) / 2;
  }
  return D;
}

ElementLaw element_law(PlaneModel model, const Material& material, Formulation formulation) {
  ElementLaw law;
  law.formulation = formulation;
  law.model = model;
  law.nu = material.nu;
  law.shear = material.E / (2 * (1 + material.nu));
  law.D = elasticity_matrix(model, material);
  if (formulation == Formulation::Mixed) {
    // D_dev = D − k m mᵀ with k = λ + 2μ/3: [[4μ/3, −2μ/3, 0], [−2μ/3, 4μ/3, 0], [0, 0, μ]],
    // written from μ alone so that it stays exact however large λ is.
    const double mu = law.shear;
    law.bulk = material.E / (3 * (1 - 2 * material.nu));
    law.D << 4 * mu / 3, -2 * mu / 3, 0,
             -2 * mu / 3, 4 * mu / 3, 0,
             0, 0, mu;
  }
  return law;
}

ElementLaw element_law(const Scene& scene) { return element_law(scene.model, scene.material, scene.body.formulation); }

Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const Eigen::Matrix3d& D,
                                  double thickness) {
  ElementLaw law;
  law.D = D;
  return element_stiffness(nodes, order, law, thickness);
}

Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const ElementLaw& law, double thickness) {
  const Eigen::Matrix<double, 2, Eigen::Dynamic> X = coordinates(nodes, order);
  const int n = 2 * static_cast<int>(X.cols());
  Eigen::MatrixXd Ke = Eigen::MatrixXd::Zero(n, n);
  const detail::QuadraturePoint* rule = nullptr;
  const int n_points = detail::triangle_rule(order, rule);
  for (int k = 0; k < n_points; ++k) {
    const StrainPoint p = strain_point(X, order, rule[k].xi, rule[k].eta);
    Ke.noalias() += (rule[k].weight * p.detJ * thickness) * (p.Bm.transpose() * law.D * p.Bm);
  }
  if (law.bulk > 0) {
    // The condensed pressure: ½ k |T| mean(tr ε)² = ½ (k/|T|) (bᵀ ue)², b = ∫ mᵀ Bm dA.
    Eigen::RowVectorXd b;
    double area = 0;
    dilatation_row(X, order, b, area);
    Ke.noalias() += (law.bulk * thickness / area) * (b.transpose() * b);
  }
  return Ke;
}

double element_mean_dilatation(const Eigen::Vector2d* nodes, int order, const Eigen::VectorXd& ue) {
  Eigen::RowVectorXd b;
  double area = 0;
  dilatation_row(coordinates(nodes, order), order, b, area);
  return b.dot(ue) / area;
}

}  // namespace contactqp
