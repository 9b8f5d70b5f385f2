// Stress recovery: σ = D ε at each element's nodes, averaged at shared nodes. With the mixed
// formulation σ = D_dev ε + p m, p = k·mean(tr ε) the element's condensed mean stress.
#include <Eigen/LU>
#include <cmath>

#include "contactqp/post.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp {
namespace {

// The element's stress from the displacement gradient grad(a, b) = d u_a / d x_b at a node,
// as rows σxx, σyy, σxy, σzz, σyz, σxz: what the element type's constitutive law makes of it
// (plane strain or stress and the mixed formulation's pressure in 2D, the 6×6 D in 3D).
class ElementStress2d {
 public:
  ElementStress2d(const ElementLaw& law, double pressure) : law_(law), D_(law.D), pressure_(pressure) {}
  Eigen::Matrix<double, 6, 1> operator()(const Eigen::Matrix2d& grad) const {
    const Eigen::Vector3d strain(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
    Eigen::Matrix<double, 6, 1> s = Eigen::Matrix<double, 6, 1>::Zero();
    s.head<3>() = D_ * strain;
    if (law_.formulation == Formulation::Mixed) {
      // σzz = p + 2μ(εzz − tr ε/3) with εzz = 0 in plane strain.
      s[0] += pressure_;
      s[1] += pressure_;
      s[3] = pressure_ - 2 * law_.shear * (strain[0] + strain[1]) / 3;
    } else {
      s[3] = law_.model == PlaneModel::PlaneStrain ? law_.nu * (s[0] + s[1]) : 0.0;
    }
    return s;
  }

 private:
  const ElementLaw& law_;
  const Eigen::Matrix3d D_;
  const double pressure_;
};

class ElementStress3d {
 public:
  explicit ElementStress3d(const ElementLaw& law) : D_(law.D) {}
  Eigen::Matrix<double, 6, 1> operator()(const Eigen::Matrix3d& grad) const {
    Eigen::Matrix<double, 6, 1> strain;
    strain << grad(0, 0), grad(1, 1), grad(2, 2), grad(1, 2) + grad(2, 1), grad(0, 2) + grad(2, 0),
        grad(0, 1) + grad(1, 0);
    const Eigen::Matrix<double, 6, 1> s = D_ * strain;  // xx, yy, zz, yz, xz, xy
    Eigen::Matrix<double, 6, 1> stored;
    stored << s[0], s[1], s[5], s[2], s[3], s[4];
    return stored;
  }

 private:
  const Eigen::Matrix<double, 6, 6> D_;
};

// Σ (element measure × the element's stress at the node) over the elements of every type.
template <int dim>
void add_elements(const Model& model, const Eigen::VectorXd& displacement, StressSums& sums) {
  const Mesh& mesh = model.mesh;
  const int npe = mesh.nodes_per_element();
  const std::vector<ElementLaw> laws = element_laws(model);
  Eigen::Matrix<double, dim, Eigen::Dynamic> X(dim, npe), U(dim, npe), dNX(dim, npe);
  std::vector<Eigen::Vector3d> nodes(npe);
  Eigen::VectorXd ue(dim * npe);
  // The shape functions' reference gradients at each node, the same for every element.
  std::vector<Eigen::Matrix<double, dim, Eigen::Dynamic>> dN(npe);
  for (int i = 0; i < npe; ++i) dN[i] = detail::cell_gradients<dim>(mesh.order, detail::cell_node<dim>(i));
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      nodes[i] = mesh.nodes[v[i]];
      X.col(i) = nodes[i].head<dim>();
      U.col(i) = displacement.segment<dim>(dim * v[i]);
      ue.segment<dim>(dim * i) = U.col(i);
    }
    const ElementLaw& law = laws[body_of_element(model, e)];
    const double measure = std::abs(element_measure(mesh, e));
    const auto stress = [&] {
      if constexpr (dim == 2) {
        const bool mixed = law.formulation == Formulation::Mixed;  // condensed mean stress, per element
        return ElementStress2d(law, mixed ? law.bulk * element_mean_dilatation(nodes.data(), mesh.order, ue) : 0.0);
      } else {
        return ElementStress3d(law);
      }
    }();
    for (int i = 0; i < npe; ++i) {
      const Eigen::Matrix<double, dim, dim> J = dN[i] * X.transpose();  // J(r, c) = d x_c / d ξ_r
      dNX.noalias() = J.inverse() * dN[i];
      const Eigen::Matrix<double, dim, dim> grad = (dNX * U.transpose()).transpose();
      sums.sum.col(v[i]) += measure * stress(grad);
      sums.weight[v[i]] += measure;
    }
  }
}

}  // namespace

StressSums stress_sums(const Model& model, const Eigen::VectorXd& displacement) {
  const int n = model.mesh.n_nodes();
  StressSums sums{Eigen::MatrixXd::Zero(6, n), Eigen::VectorXd::Zero(n)};
  if (model.dim == 2)
    add_elements<2>(model, displacement, sums);
  else
    add_elements<3>(model, displacement, sums);
  return sums;
}

NodalStress nodal_stresses(const Model& model, const Eigen::VectorXd& displacement) {
  return nodal_stresses(stress_sums(model, displacement), model.dim);
}

NodalStress nodal_stresses(const StressSums& sums, int dim) {
  const int n = static_cast<int>(sums.weight.size());
  NodalStress stress;
  for (Eigen::VectorXd* c : {&stress.xx, &stress.yy, &stress.xy, &stress.zz, &stress.yz, &stress.xz, &stress.von_mises})
    c->resize(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Matrix<double, 6, 1> s = sums.weight[k] > 0
                                              ? Eigen::Matrix<double, 6, 1>(sums.sum.col(k) / sums.weight[k])
                                              : Eigen::Matrix<double, 6, 1>::Zero();
    const double xx = s[0], yy = s[1], xy = s[2], zz = s[3], yz = s[4], xz = s[5];
    stress.xx[k] = xx;
    stress.yy[k] = yy;
    stress.xy[k] = xy;
    stress.zz[k] = zz;
    stress.yz[k] = yz;
    stress.xz[k] = xz;
    const double shear = dim == 2 ? 3 * xy * xy : 3 * (xy * xy + yz * yz + xz * xz);
    stress.von_mises[k] =
        std::sqrt(0.5 * ((xx - yy) * (xx - yy) + (yy - zz) * (yy - zz) + (zz - xx) * (zz - xx)) + shear);
  }
  return stress;
}

}  // namespace contactqp
