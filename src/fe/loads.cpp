// Force loads as consistent nodal forces f_i = ∫ N_i t ds (tractions, pressures) and
// ∫ N_i ρg dA (gravity), times the thickness, on 3-node and 6-node triangles; point forces
// at a node.
#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <set>

#include "../model/model_parts.hpp"
#include "contactqp/errors.hpp"
#include "shape_functions.hpp"

namespace contactqp::detail {
namespace {

// ∫ N_i t(x) ds over the edges of a boundary, t given per point by `traction(dx)`, where dx
// is dx/dt along the edge (body on its left, so the outward normal is (dx_y, −dx_x)/|dx|).
template <class Traction>
void add_edge_loads(const Mesh& mesh, const std::string& boundary, double thickness, Traction traction,
                    Eigen::VectorXd& f) {
  for (const BoundaryEdge& edge : mesh.boundaries.at(boundary)) {
    const Eigen::Vector2d* mid = edge.mid >= 0 ? &mesh.nodes[edge.mid] : nullptr;
    const int nodes[] = {edge.a, edge.b, edge.mid};
    for (int q = 0; q < 3; ++q) {
      const EdgePoint p = edge_point(kEdgeGaussT[q], mesh.nodes[edge.a], mesh.nodes[edge.b], mid);
      const Eigen::Vector2d t = traction(p.dx) * (kEdgeGaussW[q] * thickness);
      for (int k = 0; k < (mid ? 3 : 2); ++k) f.segment<2>(2 * nodes[k]) += p.N[k] * t;
    }
  }
}

void add_gravity(const Mesh& mesh, const LoadSpec& load, double thickness, Eigen::VectorXd& f) {
  const Eigen::Vector2d b = load.density * load.vector;  // force per volume
  std::vector<int> elements;
  if (load.region.empty()) {
    for (int e = 0; e < mesh.n_elements(); ++e) elements.push_back(e);
  } else {
    elements = mesh.regions.at(load.region);
  }
  const int npe = mesh.nodes_per_element();
  const QuadraturePoint* rule = nullptr;
  const int n_points = triangle_rule(mesh.order, rule);
  for (int e : elements) {
    const int* v = mesh.element(e);
    Eigen::Matrix<double, 2, Eigen::Dynamic> X(2, npe);
    for (int i = 0; i < npe; ++i) X.col(i) = mesh.nodes[v[i]];
    // The centroid rule integrates N_i exactly only for 3-node triangles; 6-node ones use
    // Dunavant's rule, exact for N_i on straight sides (vertices get 0, mid-sides area/3).
    for (int k = 0; k < n_points; ++k) {
      const QuadraturePoint& q = rule[k];
      const double detJ = (shape_gradients(mesh.order, q.xi, q.eta) * X.transpose()).determinant();
      const Eigen::VectorXd N = shape_values(mesh.order, q.xi, q.eta);
      for (int i = 0; i < npe; ++i) f.segment<2>(2 * v[i]) += (q.weight * detJ * thickness * N[i]) * b;
    }
  }
}

}  // namespace

std::vector<int> point_load_nodes(const Scene& scene, const Mesh& mesh, std::vector<std::string>& warnings) {
  std::vector<int> nodes(scene.loads.size(), -1);
  double extent = 0;
  for (const Eigen::Vector2d& x : mesh.nodes) extent = std::max(extent, (x - mesh.nodes[0]).norm());
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const LoadSpec& load = scene.loads[l];
    if (load.type != "point") continue;
    if (!load.point.empty()) {
      nodes[l] = mesh.points.at(load.point).front();
      continue;
    }
    double best = std::numeric_limits<double>::infinity();
    for (int node = 0; node < mesh.n_nodes(); ++node) {
      const double distance = (mesh.nodes[node] - *load.at).norm();
      if (distance < best) {
        best = distance;
        nodes[l] = node;
      }
    }
    if (best > 1e-9 * extent)
      warnings.push_back(load.path + " acts at node " + std::to_string(nodes[l]) + " at (" +
                         format_value(mesh.nodes[nodes[l]].x()) + ", " + format_value(mesh.nodes[nodes[l]].y()) +
                         "), " + format_value(best) + " from the point asked for (the nearest node)");
  }
  return nodes;
}

Eigen::VectorXd nodal_forces(const Scene& scene, const Mesh& mesh, const std::vector<int>& point_nodes) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * mesh.n_nodes());
  const double thickness = scene.body.thickness;
  std::set<int> on_symmetry_plane;
  if (scene.body.symmetry)
    for (int node : boundary_nodes(mesh, "symmetry")) on_symmetry_plane.insert(node);
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const LoadSpec& load = scene.loads[l];
    if (load.type == "traction") {
      add_edge_loads(mesh, load.boundary, thickness, [&](const Eigen::Vector2d& dx) { return Eigen::Vector2d(dx.norm() * load.vector); }, f);
    } else if (load.type == "pressure") {
      // t = −p n_out, and n_out |dx| = (dx_y, −dx_x).
      add_edge_loads(mesh, load.boundary, thickness, [&](const Eigen::Vector2d& dx) { return Eigen::Vector2d(-load.pressure * Eigen::Vector2d(dx.y(), -dx.x())); }, f);
    } else if (load.type == "gravity") {
      add_gravity(mesh, load, thickness, f);
    } else if (load.type == "point") {
      // On the symmetry plane, the modelled half carries half of the force.
      const double share = on_symmetry_plane.count(point_nodes[l]) ? 0.5 : 1.0;
      f.segment<2>(2 * point_nodes[l]) += share * load.vector;
    }
  }
  return f;
}

}  // namespace contactqp::detail
