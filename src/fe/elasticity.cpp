// Linear elasticity on the element types of the mesh (isoparametric triangles and
// tetrahedra), in the displacement formulation, and in the mixed one (P2–P0, condensed) for
// nearly incompressible plane strain.
//
// One kernel, templated on the dimension (fixed-size matrices inside, as deal.II's
// `template <int dim>`); the run-time element type picks it at the edge. The 2D instance
// uses exactly the matrix types and operations of the original triangle kernel, so a 2D
// stiffness is the same to the bit.
#include <Eigen/LU>
#include <cmath>

#include "contactqp/model.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

template <int dim>
constexpr int voigt_size() {
  return dim == 2 ? 3 : 6;
}

template <int dim>
using Coordinates = Eigen::Matrix<double, dim, Eigen::Dynamic>;

// The strain-displacement matrix at a quadrature point: ε = Bm · ue with ε = [εxx, εyy, 2εxy]
// in 2D and [εxx, εyy, εzz, 2εyz, 2εxz, 2εxy] in 3D; and |det J|.
template <int dim>
struct StrainPoint {
  Eigen::Matrix<double, voigt_size<dim>(), Eigen::Dynamic> Bm;
  double detJ = 0;
};

template <int dim>
StrainPoint<dim> strain_point(const Coordinates<dim>& X, const Eigen::Matrix<double, dim, Eigen::Dynamic>& dN) {
  const int npe = static_cast<int>(X.cols());
  const Eigen::Matrix<double, dim, dim> J = dN * X.transpose();              // J(r, c) = d x_c / d ξ_r
  const Eigen::Matrix<double, dim, Eigen::Dynamic> dNdx = J.inverse() * dN;  // rows d/dx, d/dy (, d/dz)
  StrainPoint<dim> p;
  p.detJ = std::abs(J.determinant());
  p.Bm = Eigen::Matrix<double, voigt_size<dim>(), Eigen::Dynamic>::Zero(voigt_size<dim>(), dim * npe);
  for (int i = 0; i < npe; ++i) {
    if constexpr (dim == 2) {
      p.Bm(0, 2 * i) = dNdx(0, i);
      p.Bm(1, 2 * i + 1) = dNdx(1, i);
      p.Bm(2, 2 * i) = dNdx(1, i);
      p.Bm(2, 2 * i + 1) = dNdx(0, i);
    } else {
      const int c = 3 * i;
      p.Bm(0, c) = dNdx(0, i);
      p.Bm(1, c + 1) = dNdx(1, i);
      p.Bm(2, c + 2) = dNdx(2, i);
      p.Bm(3, c + 1) = dNdx(2, i);  // 2εyz = du_y/dz + du_z/dy
      p.Bm(3, c + 2) = dNdx(1, i);
      p.Bm(4, c) = dNdx(2, i);  // 2εxz
      p.Bm(4, c + 2) = dNdx(0, i);
      p.Bm(5, c) = dNdx(1, i);  // 2εxy
      p.Bm(5, c + 1) = dNdx(0, i);
    }
  }
  return p;
}

// The quadrature points of an element type with their shape gradients, computed once.
template <int dim>
struct Rule {
  std::vector<Eigen::Matrix<double, dim, Eigen::Dynamic>> dN;
  std::vector<double> weight;
};

template <int dim>
Rule<dim> make_rule(int order) {
  Rule<dim> r;
  for (const detail::CellPoint<dim>& q : detail::cell_rule<dim>(order)) {
    r.dN.push_back(detail::cell_gradients<dim>(order, q.xi));
    r.weight.push_back(q.weight);
  }
  return r;
}

template <int dim>
const Rule<dim>& rule_of(int order) {
  static const Rule<dim> rules[2] = {make_rule<dim>(1), make_rule<dim>(2)};
  return rules[order - 1];
}

template <int dim>
Coordinates<dim> coordinates(const Eigen::Vector3d* nodes, int npe) {
  Coordinates<dim> X(dim, npe);
  for (int i = 0; i < npe; ++i) X.col(i) = nodes[i].head<dim>();
  return X;
}

// ∫_T (row of tr ε) dA = ∫ mᵀ Bm dA, and |T| (2D: the mixed formulation's dilatation).
void dilatation_row(const Coordinates<2>& X, int order, Eigen::RowVectorXd& row, double& area) {
  const Rule<2>& rule = rule_of<2>(order);
  row = Eigen::RowVectorXd::Zero(2 * X.cols());
  area = 0;
  for (size_t k = 0; k < rule.weight.size(); ++k) {
    const StrainPoint<2> p = strain_point<2>(X, rule.dN[k]);
    row += (rule.weight[k] * p.detJ) * (p.Bm.row(0) + p.Bm.row(1));
    area += rule.weight[k] * p.detJ;
  }
}

template <int dim>
Eigen::MatrixXd stiffness(const Eigen::Vector3d* nodes, int order, const ElementLaw& law, double thickness) {
  const int npe = nodes_per_element(element_type(dim, order));
  const Coordinates<dim> X = coordinates<dim>(nodes, npe);
  const int n = dim * npe;
  const Eigen::Matrix<double, voigt_size<dim>(), voigt_size<dim>()> D = law.D;
  Eigen::MatrixXd Ke = Eigen::MatrixXd::Zero(n, n);
  const Rule<dim>& rule = rule_of<dim>(order);
  for (size_t k = 0; k < rule.weight.size(); ++k) {
    const StrainPoint<dim> p = strain_point<dim>(X, rule.dN[k]);
    Ke.noalias() += (rule.weight[k] * p.detJ * thickness) * (p.Bm.transpose() * D * p.Bm);
  }
  if constexpr (dim == 2) {
    if (law.bulk > 0) {
      // The condensed pressure: ½ k |T| mean(tr ε)² = ½ (k/|T|) (bᵀ ue)², b = ∫ mᵀ Bm dA.
      Eigen::RowVectorXd b;
      double area = 0;
      dilatation_row(X, order, b, area);
      Ke.noalias() += (law.bulk * thickness / area) * (b.transpose() * b);
    }
  }
  return Ke;
}

std::vector<Eigen::Vector3d> lifted(const Eigen::Vector2d* nodes, int order) {
  std::vector<Eigen::Vector3d> x(order == 1 ? 3 : 6);
  for (size_t i = 0; i < x.size(); ++i) x[i] = Eigen::Vector3d(nodes[i].x(), nodes[i].y(), 0.0);
  return x;
}

}  // namespace

int voigt_size(int dim) { return dim == 2 ? 3 : 6; }

Eigen::MatrixXd elasticity_matrix(ElasticModel model, const Material& material) {
  const double E = material.E, nu = material.nu;
  if (model == ElasticModel::Solid) {
    const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(6, 6);
    D.topLeftCorner<3, 3>().setConstant(lambda);
    for (int i = 0; i < 3; ++i) {
      D(i, i) = lambda + 2 * mu;
      D(3 + i, 3 + i) = mu;
    }
    return D;
  }
  Eigen::Matrix3d D;
  if (model == ElasticModel::PlaneStrain) {
    const double c = E / ((1 + nu) * (1 - 2 * nu));
    D << c * (1 - nu), c * nu, 0, c * nu, c * (1 - nu), 0, 0, 0, c * (1 - 2 * nu) / 2;
  } else {
    const double c = E / (1 - nu * nu);
    D << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  }
  return D;
}

ElementLaw element_law(ElasticModel model, const Material& material, Formulation formulation) {
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
    Eigen::Matrix3d D;
    D << 4 * mu / 3, -2 * mu / 3, 0, -2 * mu / 3, 4 * mu / 3, 0, 0, 0, mu;
    law.D = D;
  }
  return law;
}

ElementLaw element_law(const Scene& scene) { return element_law(scene.model, scene.material, scene.body.formulation); }

std::vector<ElementLaw> element_laws(const Model& model) {
  if (model.bodies.empty()) return {element_law(model.scene)};
  std::vector<ElementLaw> laws;
  for (const ModelBody& body : model.bodies) laws.push_back(element_law(body.scene));
  return laws;
}

int Model::body_of_node(int node) const {
  for (size_t b = 0; b < bodies.size(); ++b)
    if (node < bodies[b].first_node + bodies[b].n_nodes) return static_cast<int>(b);
  return 0;
}

Eigen::MatrixXd element_stiffness(ElementType type, const Eigen::Vector3d* nodes, const ElementLaw& law,
                                  double thickness) {
  switch (type) {
    case ElementType::Tri3:
      return stiffness<2>(nodes, 1, law, thickness);
    case ElementType::Tri6:
      return stiffness<2>(nodes, 2, law, thickness);
    case ElementType::Tet4:
      return stiffness<3>(nodes, 1, law, 1.0);
    case ElementType::Tet10:
      return stiffness<3>(nodes, 2, law, 1.0);
  }
  return {};
}

Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const Eigen::Matrix3d& D, double thickness) {
  ElementLaw law;
  law.D = D;
  return element_stiffness(nodes, order, law, thickness);
}

Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const ElementLaw& law, double thickness) {
  return element_stiffness(element_type(2, order), lifted(nodes, order).data(), law, thickness);
}

double element_mean_dilatation(const Eigen::Vector3d* nodes, int order, const Eigen::VectorXd& ue) {
  Eigen::RowVectorXd b;
  double area = 0;
  dilatation_row(coordinates<2>(nodes, order == 1 ? 3 : 6), order, b, area);
  return b.dot(ue) / area;
}

double element_mean_dilatation(const Eigen::Vector2d* nodes, int order, const Eigen::VectorXd& ue) {
  return element_mean_dilatation(lifted(nodes, order).data(), order, ue);
}

}  // namespace contactqp
