// Force loads as consistent nodal forces f_i = ∫ N_i t ds (tractions, pressures) and
// ∫ N_i ρg dA (gravity), times the thickness in 2D, on every element type and its faces
// (edges in 2D, triangles in 3D); point forces at a node.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "contactqp/errors.hpp"
#include "model/model_parts.hpp"
#include "shape_functions.hpp"

namespace contactqp::detail {
namespace {

// ∫ N_i t(x) ds over the edges of a 2D boundary, t given per point by `traction(dx)`, where
// dx is dx/dt along the edge (body on its left, so the outward normal is (dx_y, −dx_x)/|dx|).
template <class Traction>
void add_edge_loads(const Mesh& mesh, const std::string& boundary, double thickness, Traction traction,
                    Eigen::VectorXd& f) {
  for (const BoundaryFace& edge : mesh.boundaries.at(boundary)) {
    const bool quadratic = edge.n_nodes == 3;
    const Eigen::Vector3d* mid = quadratic ? &mesh.nodes[edge.nodes[2]] : nullptr;
    for (int q = 0; q < 3; ++q) {
      const EdgePoint p = edge_point(kEdgeGaussT[q], mesh.nodes[edge.nodes[0]], mesh.nodes[edge.nodes[1]], mid);
      const Eigen::Vector2d t = traction(Eigen::Vector2d(p.dx.head<2>())) * (kEdgeGaussW[q] * thickness);
      for (int k = 0; k < edge.n_nodes; ++k) f.segment<2>(2 * edge.nodes[k]) += p.N[k] * t;
    }
  }
}

// ∫ N_i t(x) dA over the triangular faces of a 3D boundary, t given per point by
// `traction(a)`, where a = ∂x/∂ξ × ∂x/∂η is the outward area vector per reference area.
template <class Traction>
void add_face_loads(const Mesh& mesh, const std::string& boundary, Traction traction, Eigen::VectorXd& f) {
  const int order = mesh.order;
  const QuadraturePoint* rule = nullptr;
  const int n_points = triangle_rule(order, rule);
  for (const BoundaryFace& face : mesh.boundaries.at(boundary)) {
    Eigen::Matrix<double, 3, Eigen::Dynamic> X(3, face.n_nodes);
    for (int k = 0; k < face.n_nodes; ++k) X.col(k) = mesh.nodes[face.nodes[k]];
    for (int q = 0; q < n_points; ++q) {
      const Eigen::VectorXd N = shape_values(order, rule[q].xi, rule[q].eta);
      const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(order, rule[q].xi, rule[q].eta);
      const Eigen::Vector3d a =
          Eigen::Vector3d(X * dN.row(0).transpose()).cross(Eigen::Vector3d(X * dN.row(1).transpose()));
      const Eigen::Vector3d t = traction(a) * rule[q].weight;
      for (int k = 0; k < face.n_nodes; ++k) f.segment<3>(3 * face.nodes[k]) += N[k] * t;
    }
  }
}

void add_gravity(const Mesh& mesh, const GravityLoad& load, double thickness, Eigen::VectorXd& f) {
  const Eigen::Vector3d b = load.density * load.g;  // force per volume
  std::vector<int> elements;
  if (load.region.empty()) {
    for (int e = 0; e < mesh.n_elements(); ++e) elements.push_back(e);
  } else {
    elements = mesh.regions.at(load.region);
  }
  const int npe = mesh.nodes_per_element();
  if (mesh.dim == 2) {
    const Eigen::Vector2d b2 = b.head<2>();
    const QuadraturePoint* rule = nullptr;
    const int n_points = triangle_rule(mesh.order, rule);
    for (int e : elements) {
      const int* v = mesh.element(e);
      Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe);
      for (int i = 0; i < npe; ++i) X.col(i) = mesh.nodes[v[i]].head<2>();
      // The centroid rule integrates N_i exactly only for 3-node triangles; 6-node ones use
      // Dunavant's rule, exact for N_i on straight sides (vertices get 0, mid-sides area/3).
      for (int k = 0; k < n_points; ++k) {
        const QuadraturePoint& q = rule[k];
        const double detJ = (shape_gradients(mesh.order, q.xi, q.eta) * X.transpose()).determinant();
        const Eigen::VectorXd N = shape_values(mesh.order, q.xi, q.eta);
        for (int i = 0; i < npe; ++i) f.segment<2>(2 * v[i]) += (q.weight * detJ * thickness * N[i]) * b2;
      }
    }
    return;
  }
  // Tetrahedra: the centroid rule is exact for ∫ N_i of a straight 4-node one, the 4-point
  // degree-2 rule for a straight 10-node one (vertices −V/20, mid-edges V/5).
  const TetrahedronPoint* rule = nullptr;
  const int n_points = tetrahedron_rule(mesh.order, rule);
  for (int e : elements) {
    const int* v = mesh.element(e);
    Eigen::Matrix<double, 3, Eigen::Dynamic> X(3, npe);
    for (int i = 0; i < npe; ++i) X.col(i) = mesh.nodes[v[i]];
    for (int k = 0; k < n_points; ++k) {
      const TetrahedronPoint& q = rule[k];
      const double detJ = (tetrahedron_gradients(mesh.order, q.xi, q.eta, q.zeta) * X.transpose()).determinant();
      const Eigen::VectorXd N = tetrahedron_values(mesh.order, q.xi, q.eta, q.zeta);
      for (int i = 0; i < npe; ++i) f.segment<3>(3 * v[i]) += (q.weight * detJ * N[i]) * b;
    }
  }
}

}  // namespace

std::vector<int> point_load_nodes(const Scene& scene, const Mesh& mesh, std::vector<std::string>& warnings) {
  std::vector<int> nodes(scene.loads.size(), -1);
  double extent = 0;
  for (const Eigen::Vector3d& x : mesh.nodes) extent = std::max(extent, (x - mesh.nodes[0]).norm());
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const PointLoad* point = scene.loads[l].as<PointLoad>();
    if (!point) continue;
    if (!point->point.empty()) {
      nodes[l] = mesh.points.at(point->point).front();
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (int node = 0; node < mesh.n_nodes(); ++node) {
      const double distance = (mesh.nodes[node] - *point->at).norm();
      if (distance < best) {
        best = distance;
        nodes[l] = node;
      }
    }
    if (best > 1e-9 * extent)
      warnings.push_back(scene.loads[l].path + " acts at node " + std::to_string(nodes[l]) + " at " +
                         format_point(mesh.nodes[nodes[l]], mesh.dim) + ", " + format_value(best) +
                         " from the point asked for (the nearest node)");
  }
  return nodes;
}

Eigen::VectorXd nodal_forces(const Scene& scene, const Mesh& mesh, const std::vector<int>& point_nodes) {
  const int dim = mesh.dim;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dim * mesh.n_nodes());
  const double thickness = scene.body.thickness;
  // A point load on a symmetry plane: the modelled part carries its share of the force
  // (half on one plane, a quarter on the axis where two planes meet).
  std::vector<int> planes_of_node(mesh.n_nodes(), 0);
  if (scene.body.symmetry)
    for (const std::string& plane : symmetry_boundaries(dim))
      for (int node : boundary_nodes(mesh, plane)) ++planes_of_node[node];
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const LoadSpec& load = scene.loads[l];
    if (const auto* traction = load.as<TractionLoad>()) {
      const Eigen::Vector3d& t = traction->traction;
      if (dim == 2)
        add_edge_loads(
            mesh, traction->boundary, thickness,
            [&](const Eigen::Vector2d& dx) { return Eigen::Vector2d(dx.norm() * t.head<2>()); }, f);
      else
        add_face_loads(
            mesh, traction->boundary, [&](const Eigen::Vector3d& a) { return Eigen::Vector3d(a.norm() * t); }, f);
    } else if (const auto* pressure = load.as<PressureLoad>()) {
      // t = −p n_out; in 2D n_out |dx| = (dx_y, −dx_x), in 3D n_out |a| = a.
      const double p = pressure->pressure;
      if (dim == 2)
        add_edge_loads(
            mesh, pressure->boundary, thickness,
            [&](const Eigen::Vector2d& dx) { return Eigen::Vector2d(-p * Eigen::Vector2d(dx.y(), -dx.x())); }, f);
      else
        add_face_loads(
            mesh, pressure->boundary, [&](const Eigen::Vector3d& a) { return Eigen::Vector3d(-p * a); }, f);
    } else if (const auto* gravity = load.as<GravityLoad>()) {
      add_gravity(mesh, *gravity, thickness, f);
    } else if (const auto* point = load.as<PointLoad>()) {
      const double share = std::pow(0.5, planes_of_node[point_nodes[l]]);
      f.segment(dim * point_nodes[l], dim) += share * point->force.head(dim);
    }
  }
  return f;
}

std::vector<LoadShare> load_shares(const Model& model, const std::vector<int>& point_nodes) {
  const int dim = model.mesh.dim;
  std::vector<LoadShare> shares;
  for (size_t l = 0; l < model.scene.loads.size(); ++l) {
    const LoadSpec& load = model.scene.loads[l];
    Scene one = model.scene;  // the load alone
    one.loads = {load};
    LoadShare share;
    share.nodal_force = nodal_forces(one, model.mesh, {point_nodes[l]});
    if (const auto* d = load.as<DisplacementLoad>())
      for (int node : boundary_nodes(model.mesh, d->boundary))
        for (int c = 0; c < dim; ++c)
          if (d->value[c]) share.prescribed.emplace_back(dim * node + c, *d->value[c]);
    shares.push_back(std::move(share));
  }
  return shares;
}

}  // namespace contactqp::detail
