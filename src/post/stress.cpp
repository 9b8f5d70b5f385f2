// Stress recovery: σ = D ε at each element's nodes, averaged at shared nodes. With the mixed
// formulation σ = D_dev ε + p m, p = k·mean(tr ε) the element's condensed mean stress.
#include <Eigen/LU>
#include <cmath>

#include "contactqp/post.hpp"
#include "fe/shape_functions.hpp"

namespace contactqp {
namespace {

void add_triangles(const Model& model, const Eigen::VectorXd& displacement, StressSums& sums) {
  const Mesh& mesh = model.mesh;
  const int npe = mesh.nodes_per_element();
  const std::vector<ElementLaw> laws = element_laws(model);
  Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe), U(2, npe);
  std::vector<Eigen::Vector3d> nodes(npe);
  Eigen::VectorXd ue(2 * npe);
  // The shape functions' reference gradients at each node, the same for every element.
  std::vector<Eigen::Matrix<double, 2, Eigen::Dynamic>> dN(npe);
  for (int i = 0; i < npe; ++i) {
    const Eigen::Vector2d at = detail::reference_node(i);
    dN[i] = detail::shape_gradients(mesh.order, at.x(), at.y());
  }
  Eigen::Matrix<double, 2, Eigen::Dynamic> dNX(2, npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      nodes[i] = mesh.nodes[v[i]];
      X.col(i) = nodes[i].head<2>();
      U.col(i) = displacement.segment<2>(2 * v[i]);
      ue.segment<2>(2 * i) = U.col(i);
    }
    const ElementLaw& law = laws[body_of_element(model, e)];
    const Eigen::Matrix3d D = law.D;
    const bool mixed = law.formulation == Formulation::Mixed;
    const double area = std::abs(element_area(mesh, e));
    const double pressure = mixed ? law.bulk * element_mean_dilatation(nodes.data(), mesh.order, ue) : 0.0;
    for (int i = 0; i < npe; ++i) {
      const Eigen::Matrix2d J = dN[i] * X.transpose();  // J(r, c) = d x_c / d ξ_r
      dNX.noalias() = J.inverse() * dN[i];
      const Eigen::Matrix2d grad = (dNX * U.transpose()).transpose();  // grad(a, b) = d u_a / d x_b
      const Eigen::Vector3d strain(grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0));
      Eigen::Vector4d s;
      s.head<3>() = D * strain;
      if (mixed) {
        // σzz = p + 2μ(εzz − tr ε/3) with εzz = 0 in plane strain.
        s[0] += pressure;
        s[1] += pressure;
        s[3] = pressure - 2 * law.shear * (strain[0] + strain[1]) / 3;
      } else {
        s[3] = law.model == PlaneModel::PlaneStrain ? law.nu * (s[0] + s[1]) : 0.0;
      }
      sums.sum.col(v[i]).head<4>() += area * s;
      sums.weight[v[i]] += area;
    }
  }
}

void add_tetrahedra(const Model& model, const Eigen::VectorXd& displacement, StressSums& sums) {
  const Mesh& mesh = model.mesh;
  const int npe = mesh.nodes_per_element();
  const std::vector<ElementLaw> laws = element_laws(model);
  Eigen::Matrix<double, 3, Eigen::Dynamic> X(3, npe), U(3, npe);
  std::vector<Eigen::Matrix<double, 3, Eigen::Dynamic>> dN(npe);  // as in add_triangles
  for (int i = 0; i < npe; ++i) {
    const Eigen::Vector3d at = detail::reference_tetrahedron_node(i);
    dN[i] = detail::tetrahedron_gradients(mesh.order, at.x(), at.y(), at.z());
  }
  Eigen::Matrix<double, 3, Eigen::Dynamic> dNX(3, npe);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) {
      X.col(i) = mesh.nodes[v[i]];
      U.col(i) = displacement.segment<3>(3 * v[i]);
    }
    const Eigen::Matrix<double, 6, 6> D = laws[body_of_element(model, e)].D;
    const double volume = std::abs(element_measure(mesh, e));
    for (int i = 0; i < npe; ++i) {
      const Eigen::Matrix3d J = dN[i] * X.transpose();
      dNX.noalias() = J.inverse() * dN[i];
      const Eigen::Matrix3d grad = (dNX * U.transpose()).transpose();  // grad(a, b) = d u_a / d x_b
      Eigen::Matrix<double, 6, 1> strain;
      strain << grad(0, 0), grad(1, 1), grad(2, 2), grad(1, 2) + grad(2, 1), grad(0, 2) + grad(2, 0),
          grad(0, 1) + grad(1, 0);
      const Eigen::Matrix<double, 6, 1> s = D * strain;  // xx, yy, zz, yz, xz, xy
      Eigen::Matrix<double, 6, 1> stored;
      stored << s[0], s[1], s[5], s[2], s[3], s[4];  // rows xx, yy, xy, zz, yz, xz
      sums.sum.col(v[i]) += volume * stored;
      sums.weight[v[i]] += volume;
    }
  }
}

}  // namespace

StressSums stress_sums(const Model& model, const Eigen::VectorXd& displacement) {
  const int n = model.mesh.n_nodes();
  StressSums sums{Eigen::MatrixXd::Zero(6, n), Eigen::VectorXd::Zero(n)};
  if (model.dim == 2)
    add_triangles(model, displacement, sums);
  else
    add_tetrahedra(model, displacement, sums);
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
