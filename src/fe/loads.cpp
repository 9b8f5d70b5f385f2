// Force loads as consistent nodal forces f_i = ∫ N_i t ds (tractions, pressures) and
// ∫ N_i ρg dA (gravity), times the thickness in 2D, on every element type and its faces
// (edges in 2D, triangles in 3D); point forces at a node.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "contactqp/errors.hpp"
#include "fe/loads.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp::detail {
namespace {

// A quadrature point of a boundary face — an edge in 2D, a triangle in 3D: the face's shape
// values there, its area vector a (the outward normal times the face's measure per unit of the
// rule's: (dx_y, −dx_x, 0) along an edge with the body on its left, ∂x/∂ξ × ∂x/∂η on a triangle)
// and the rule's weight.
struct FacePoint {
  Eigen::VectorXd N;
  Eigen::Vector3d a;
  double weight;
};

std::vector<FacePoint> face_points(const Mesh& mesh, const BoundaryFace& face) {
  std::vector<FacePoint> points;
  if (mesh.dim == 2) {  // Gauss–Legendre, 3 points along the edge (a, b, mid-side node)
    const Eigen::Vector3d* mid = face.n_nodes == 3 ? &mesh.nodes[face.nodes[2]] : nullptr;
    for (int q = 0; q < 3; ++q) {
      const EdgePoint p = edge_point(kEdgeGaussT[q], mesh.nodes[face.nodes[0]], mesh.nodes[face.nodes[1]], mid);
      points.push_back({Eigen::Map<const Eigen::VectorXd>(p.N, face.n_nodes), Eigen::Vector3d(p.dx.y(), -p.dx.x(), 0.0),
                        kEdgeGaussW[q]});
    }
    return points;
  }
  const QuadraturePoint* rule = nullptr;
  const int n_points = triangle_rule(mesh.order, rule);
  Eigen::Matrix<double, 3, Eigen::Dynamic> X(3, face.n_nodes);
  for (int k = 0; k < face.n_nodes; ++k) X.col(k) = mesh.nodes[face.nodes[k]];
  for (int q = 0; q < n_points; ++q) {
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(mesh.order, rule[q].xi, rule[q].eta);
    points.push_back({shape_values(mesh.order, rule[q].xi, rule[q].eta),
                      Eigen::Vector3d(X * dN.row(0).transpose()).cross(Eigen::Vector3d(X * dN.row(1).transpose())),
                      rule[q].weight});
  }
  return points;
}

// ∫ N_i t(x) dA over the faces of a boundary, t given per point by `traction(a)` (a the area
// vector above), times the thickness in 2D.
template <class Traction>
void add_boundary_loads(const Mesh& mesh, const std::string& boundary, double thickness, Traction traction,
                        Eigen::VectorXd& f) {
  const int dim = mesh.dim;
  for (const BoundaryFace& face : mesh.boundaries.at(boundary))
    for (const FacePoint& p : face_points(mesh, face)) {
      const Eigen::Vector3d t = traction(p.a) * (p.weight * thickness);
      for (int k = 0; k < face.n_nodes; ++k) f.segment(dim * face.nodes[k], dim) += p.N[k] * t.head(dim);
    }
}

// ∫ N_i b dV over `elements` (b the force per volume), times the thickness in 2D. The
// centroid rule integrates N_i exactly for 3-node triangles and 4-node tetrahedra; 6-node
// triangles use Dunavant's rule, exact for N_i on straight sides (vertices get 0, mid-sides
// area/3), 10-node tetrahedra the 4-point degree-2 rule, exact for straight ones (vertices
// −V/20, mid-edges V/5).
template <int dim>
void add_body_force(const Mesh& mesh, const std::vector<int>& elements, const Eigen::Vector3d& b3, double thickness,
                    Eigen::VectorXd& f) {
  const Eigen::Matrix<double, dim, 1> b = b3.head<dim>();
  const int npe = mesh.nodes_per_element();
  const std::vector<CellPoint<dim>> rule = cell_rule<dim>(mesh.order);
  Eigen::Matrix<double, dim, Eigen::Dynamic> X(dim, npe);
  for (int e : elements) {
    const int* v = mesh.element(e);
    for (int i = 0; i < npe; ++i) X.col(i) = mesh.nodes[v[i]].head<dim>();
    for (const CellPoint<dim>& q : rule) {
      const double detJ = (cell_gradients<dim>(mesh.order, q.xi) * X.transpose()).determinant();
      const Eigen::VectorXd N = cell_values<dim>(mesh.order, q.xi);
      for (int i = 0; i < npe; ++i) f.segment<dim>(dim * v[i]) += (q.weight * detJ * thickness * N[i]) * b;
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
  if (mesh.dim == 2)
    add_body_force<2>(mesh, elements, b, thickness, f);
  else
    add_body_force<3>(mesh, elements, b, thickness, f);
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

Eigen::Vector3d boundary_centroid(const Mesh& mesh, const std::string& boundary) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double measure = 0;
  for (const BoundaryFace& face : mesh.boundaries.at(boundary))
    for (const FacePoint& p : face_points(mesh, face)) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int k = 0; k < face.n_nodes; ++k) x += p.N[k] * mesh.nodes[face.nodes[k]];
      sum += p.a.norm() * p.weight * x;
      measure += p.a.norm() * p.weight;
    }
  return measure > 0 ? Eigen::Vector3d(sum / measure) : sum;
}

Eigen::VectorXd nodal_forces(const Scene& scene, const Mesh& mesh, const std::vector<int>& point_nodes) {
  const int dim = mesh.dim;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dim * mesh.n_nodes());
  const double thickness = dim == 2 ? scene.body.thickness : 1.0;  // 3D: forces are not per a thickness
  // A point load on a symmetry plane: the modelled part carries its share of the force
  // (half on one plane, a quarter on the axis where two planes meet).
  std::vector<int> planes_of_node(mesh.n_nodes(), 0);
  for (const std::string& plane : symmetry_boundaries(scene.body, dim))
    for (int node : boundary_nodes(mesh, plane)) ++planes_of_node[node];
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const LoadSpec& load = scene.loads[l];
    if (const auto* traction = load.as<TractionLoad>()) {
      const Eigen::Vector3d& t = traction->traction;
      add_boundary_loads(
          mesh, traction->boundary, thickness, [&](const Eigen::Vector3d& a) { return Eigen::Vector3d(a.norm() * t); },
          f);
    } else if (const auto* pressure = load.as<PressureLoad>()) {
      // t = −p n_out, and n_out times the measure is a.
      const double p = pressure->pressure;
      add_boundary_loads(
          mesh, pressure->boundary, thickness, [&](const Eigen::Vector3d& a) { return Eigen::Vector3d(-p * a); }, f);
    } else if (const auto* gravity = load.as<GravityLoad>()) {
      add_gravity(mesh, *gravity, thickness, f);
    } else if (const auto* point = load.as<PointLoad>()) {
      const double share = std::pow(0.5, planes_of_node[point_nodes[l]]);
      f.segment(dim * point_nodes[l], dim) += share * point->force.head(dim);
    }
  }
  return f;
}

}  // namespace contactqp::detail
