// Rows between two bodies: node-to-segment (2D) and node-to-face (3D) under small slip
// (docs/bodies.md). A candidate node i of one side is projected once, in the initial
// configuration, to the closest point ξ of the other side's boundary; the row keeps that ξ and
// the face's outward normal n there: −nᵀ(u_i − Σ_j N_j(ξ) u_j) ≤ g_i, g_i = (x_i − x(ξ))·n.
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "contact.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp::detail {
namespace {

// A closest point within 1e-9 of a vertex (in the face's parameters) is that vertex: the node
// then faces the vertex along the boundary's averaged normal there, so that two identical
// meshes mirrored onto each other give the same row from either side.
constexpr double kSnap = 1e-9;

Eigen::Vector3d edge_normal(const Eigen::Vector3d& tangent) {
  return Eigen::Vector3d(tangent.y(), -tangent.x(), 0.0).normalized();  // the body lies left of a → b
}

// The point of the 3D triangle (a, b, c) closest to p, as barycentric weights of (a, b, c)
// (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denominator = 1 / (va + vb + vc);
  const double v = vb * denominator, w = vc * denominator;
  return {1 - v - w, v, w};
}

}  // namespace

FaceProjection project_to_face(const std::vector<Eigen::Vector3d>& x, const BoundaryFace& face, int dim,
                               const Eigen::Vector3d& p) {
  FaceProjection out;
  out.n_nodes = face.n_nodes;
  const auto& v = face.nodes;
  if (dim == 2) {
    const Eigen::Vector3d &a = x[v[0]], &b = x[v[1]];
    const Eigen::Vector3d* m = face.n_nodes == 3 ? &x[v[2]] : nullptr;
    double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    if (m) {  // Newton on ½|x(t) − p|²; x'' = 4a + 4b − 8m is constant
      const Eigen::Vector3d second = 4 * a + 4 * b - 8 * *m;
      for (int k = 0; k < 30; ++k) {
        const EdgePoint e = edge_point(t, a, b, m);
        const Eigen::Vector3d xt = e.N[0] * a + e.N[1] * b + e.N[2] * *m;
        const double slope = (xt - p).dot(e.dx), curvature = e.dx.squaredNorm() + (xt - p).dot(second);
        const double next = std::clamp(t - slope / std::max(curvature, 1e-300), 0.0, 1.0);
        const bool done = std::abs(next - t) < 1e-15;
        t = next;
        if (done) break;
      }
    }
    out.parameters = Eigen::Vector2d(t, 0);
    const EdgePoint e = edge_point(t, a, b, m);
    for (int k = 0; k < face.n_nodes; ++k) out.weights[k] = e.N[k];
    out.point = e.N[0] * a + e.N[1] * b;
    if (m) out.point += e.N[2] * *m;
    out.normal = edge_normal(e.dx);
    out.vertex = t < kSnap ? 0 : (t > 1 - kSnap ? 1 : -1);
    return out;
  }
  const Eigen::Vector3d bary = closest_on_triangle(p, x[v[0]], x[v[1]], x[v[2]]);
  double xi = bary[1], eta = bary[2];
  const int order = face.n_nodes == 6 ? 2 : 1;
  Eigen::Matrix<double, 3, 6> X = Eigen::Matrix<double, 3, 6>::Zero();
  for (int k = 0; k < face.n_nodes; ++k) X.col(k) = x[v[k]];
  auto point_at = [&](double s, double r, Eigen::VectorXd& N, Eigen::Matrix<double, 3, 2>& J) {
    N = shape_values(order, s, r);
    const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(order, s, r);
    J = X.leftCols(face.n_nodes) * dN.transpose();
    return Eigen::Vector3d(X.leftCols(face.n_nodes) * N);
  };
  Eigen::VectorXd N;
  Eigen::Matrix<double, 3, 2> J;
  if (order == 2) {  // Gauss–Newton from the flat triangle's closest point, kept on the face
    for (int k = 0; k < 30; ++k) {
      const Eigen::Vector3d r = point_at(xi, eta, N, J) - p;
      const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(-J.transpose() * r);
      double s = std::max(0.0, xi + step[0]), q = std::max(0.0, eta + step[1]);
      if (s + q > 1) {
        const double total = s + q;
        s /= total;
        q /= total;
      }
      const bool done = std::abs(s - xi) + std::abs(q - eta) < 1e-15;
      xi = s;
      eta = q;
      if (done) break;
    }
  }
  out.point = point_at(xi, eta, N, J);
  for (int k = 0; k < face.n_nodes; ++k) out.weights[k] = N[k];
  out.normal = J.col(0).cross(J.col(1)).normalized();
  out.parameters = Eigen::Vector2d(xi, eta);
  const double lambda[3] = {1 - xi - eta, xi, eta};
  for (int k = 0; k < 3; ++k)
    if (lambda[k] > 1 - kSnap) out.vertex = k;
  return out;
}

double smallest_face_size(const Mesh& mesh, const std::string& boundary) {
  double smallest = std::numeric_limits<double>::infinity();
  auto it = mesh.boundaries.find(boundary);
  if (it == mesh.boundaries.end()) return smallest;
  for (const BoundaryFace& face : it->second) {
    const auto& x = mesh.nodes;
    const auto& v = face.nodes;
    const double size =
        mesh.dim == 2 ? (x[v[1]] - x[v[0]]).norm()
                      : ((x[v[1]] - x[v[0]]).norm() + (x[v[2]] - x[v[1]]).norm() + (x[v[0]] - x[v[2]]).norm()) / 3.0;
    smallest = std::min(smallest, size);
  }
  return smallest;
}

ClosestFace closest_face(const std::vector<Eigen::Vector3d>& x, const std::vector<BoundaryFace>& faces, int dim,
                         const Eigen::Vector3d& p) {
  ClosestFace best;
  best.distance = std::numeric_limits<double>::infinity();
  for (size_t f = 0; f < faces.size(); ++f) {
    const BoundaryFace& face = faces[f];
    // A face whose bounding box is farther than the best distance cannot be closer.
    Eigen::Vector3d lo = x[face.nodes[0]], hi = lo;
    for (int k = 1; k < face.n_nodes; ++k) {
      lo = lo.cwiseMin(x[face.nodes[k]]);
      hi = hi.cwiseMax(x[face.nodes[k]]);
    }
    const Eigen::Vector3d outside = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
    if (outside.norm() > best.distance) continue;
    const FaceProjection projection = project_to_face(x, face, dim, p);
    const double distance = (p - projection.point).norm();
    if (distance < best.distance) {
      best.distance = distance;
      best.face = static_cast<int>(f);
      best.projection = projection;
    }
  }
  return best;
}

namespace {

// Where the line x(t) = p − t·d meets a face (unclamped face parameters), by Newton on
// x(ξ) − p + t d = 0 from the flat face's solution; nullopt when the line runs along the face.
struct LineHit {
  Eigen::Vector2d parameters;
  double t = 0;
};
std::optional<LineHit> line_meets_face(const std::vector<Eigen::Vector3d>& x, const BoundaryFace& face, int dim,
                                       const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  const auto& v = face.nodes;
  const int order = (dim == 2 ? face.n_nodes == 3 : face.n_nodes == 6) ? 2 : 1;
  Eigen::Vector2d xi = dim == 2 ? Eigen::Vector2d(0.5, 0) : Eigen::Vector2d(1.0 / 3, 1.0 / 3);
  double t = 0;
  for (int k = 0; k < (order == 1 ? 1 : 12); ++k) {
    Eigen::Vector3d point, dx0, dx1 = Eigen::Vector3d::Zero();
    if (dim == 2) {
      const EdgePoint e = edge_point(xi[0], x[v[0]], x[v[1]], order == 2 ? &x[v[2]] : nullptr);
      point = e.N[0] * x[v[0]] + e.N[1] * x[v[1]];
      if (order == 2) point += e.N[2] * x[v[2]];
      dx0 = e.dx;
    } else {
      const Eigen::VectorXd N = shape_values(order, xi[0], xi[1]);
      const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(order, xi[0], xi[1]);
      point.setZero();
      dx0.setZero();
      for (int j = 0; j < face.n_nodes; ++j) {
        point += N[j] * x[v[j]];
        dx0 += dN(0, j) * x[v[j]];
        dx1 += dN(1, j) * x[v[j]];
      }
    }
    const Eigen::Vector3d residual = point - p + t * d;
    Eigen::Vector3d step;
    if (dim == 2) {
      Eigen::Matrix2d J;
      J << dx0.head<2>(), d.head<2>();
      if (std::abs(J.determinant()) < 1e-14 * dx0.norm()) return std::nullopt;
      const Eigen::Vector2d s = J.partialPivLu().solve(-residual.head<2>());
      step = Eigen::Vector3d(s[0], 0, s[1]);
    } else {
      Eigen::Matrix3d J;
      J << dx0, dx1, d;
      if (std::abs(J.determinant()) < 1e-14 * dx0.cross(dx1).norm()) return std::nullopt;
      step = J.partialPivLu().solve(-residual);
    }
    xi += step.head<2>();
    t += step[2];
    if (step.head<2>().norm() < 1e-15) break;
  }
  return LineHit{xi, t};
}

bool inside(const Eigen::Vector2d& xi, int dim, double tolerance) {
  if (dim == 2) return xi[0] >= -tolerance && xi[0] <= 1 + tolerance;
  return xi[0] >= -tolerance && xi[1] >= -tolerance && xi[0] + xi[1] <= 1 + tolerance;
}

}  // namespace

std::optional<FaceProjection> project_along_common_normal(const Mesh& mesh, const std::vector<BoundaryFace>& faces,
                                                          const std::map<int, Eigen::Vector3d>& vertex_normal,
                                                          const Eigen::Vector3d& p, const Eigen::Vector3d& node_normal,
                                                          const ClosestFace& closest) {
  const int dim = mesh.dim;
  // The faces near the closest point: within a few times the distance and the face's size.
  const BoundaryFace& start = faces[closest.face];
  double reach = closest.distance;
  for (int k = 1; k < start.n_nodes; ++k)
    reach = std::max(reach, 2 * (mesh.nodes[start.nodes[k]] - mesh.nodes[start.nodes[0]]).norm() + closest.distance);
  std::vector<int> near;
  for (size_t f = 0; f < faces.size(); ++f) {
    Eigen::Vector3d lo = mesh.nodes[faces[f].nodes[0]], hi = lo;
    for (int k = 1; k < faces[f].n_nodes; ++k) {
      lo = lo.cwiseMin(mesh.nodes[faces[f].nodes[k]]);
      hi = hi.cwiseMax(mesh.nodes[faces[f].nodes[k]]);
    }
    if ((lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm() <= 2 * reach) near.push_back(static_cast<int>(f));
  }
  // The other side's normal interpolated from its vertex normals (continuous across faces).
  auto smooth_normal = [&](const BoundaryFace& face, const std::array<double, 6>& weights) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int k = 0; k < face.n_nodes; ++k) n += weights[k] * vertex_normal.at(face.nodes[k]);
    return Eigen::Vector3d(n.normalized());
  };
  FaceProjection current = closest.projection;
  int current_face = closest.face;
  for (int iteration = 0; iteration < 8; ++iteration) {
    const Eigen::Vector3d d = (smooth_normal(faces[current_face], current.weights) - node_normal).normalized();
    int best = -1;
    LineHit best_hit;
    for (int f : near) {
      const auto hit = line_meets_face(mesh.nodes, faces[f], dim, p, d);
      if (!hit || !inside(hit->parameters, dim, 1e-12)) continue;
      if (best < 0 || std::abs(hit->t) < std::abs(best_hit.t)) {
        best = f;
        best_hit = *hit;
      }
    }
    if (best < 0) return std::nullopt;
    // The face's own projection machinery gives weights, point and normal at the parameters.
    FaceProjection next;
    const BoundaryFace& face = faces[best];
    Eigen::Vector2d xi = best_hit.parameters;
    if (dim == 2)
      xi[0] = std::clamp(xi[0], 0.0, 1.0);
    else {
      xi = xi.cwiseMax(0.0);
      if (xi.sum() > 1) xi /= xi.sum();
    }
    next = project_to_face(mesh.nodes, face, dim, p);  // for n_nodes; overwritten below
    const int order = (dim == 2 ? face.n_nodes == 3 : face.n_nodes == 6) ? 2 : 1;
    next.point.setZero();
    next.weights.fill(0.0);
    if (dim == 2) {
      const EdgePoint e = edge_point(xi[0], mesh.nodes[face.nodes[0]], mesh.nodes[face.nodes[1]],
                                     order == 2 ? &mesh.nodes[face.nodes[2]] : nullptr);
      for (int k = 0; k < face.n_nodes; ++k) next.weights[k] = e.N[k];
      next.normal = Eigen::Vector3d(e.dx.y(), -e.dx.x(), 0.0).normalized();
      next.vertex = xi[0] < 1e-9 ? 0 : (xi[0] > 1 - 1e-9 ? 1 : -1);
    } else {
      const Eigen::VectorXd N = shape_values(order, xi[0], xi[1]);
      const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(order, xi[0], xi[1]);
      Eigen::Vector3d dx0 = Eigen::Vector3d::Zero(), dx1 = Eigen::Vector3d::Zero();
      for (int k = 0; k < face.n_nodes; ++k) {
        next.weights[k] = N[k];
        dx0 += dN(0, k) * mesh.nodes[face.nodes[k]];
        dx1 += dN(1, k) * mesh.nodes[face.nodes[k]];
      }
      next.normal = dx0.cross(dx1).normalized();
      const double lambda[3] = {1 - xi[0] - xi[1], xi[0], xi[1]};
      next.vertex = -1;
      for (int k = 0; k < 3; ++k)
        if (lambda[k] > 1 - 1e-9) next.vertex = k;
    }
    for (int k = 0; k < face.n_nodes; ++k) next.point += next.weights[k] * mesh.nodes[face.nodes[k]];
    next.parameters = xi;
    const bool settled = best == current_face && (next.parameters - current.parameters).norm() < 1e-13;
    current = next;
    current_face = best;
    if (settled) break;
  }
  current.n_nodes = faces[current_face].n_nodes;
  current.parameters[1] = current.parameters[1];
  // Record which face in the vertex slot's sense: the caller reads `face` from here.
  current.face = current_face;
  return current;
}

std::vector<Candidate> select_pair_candidates(const Mesh& mesh, const std::string& node_boundary,
                                              const std::string& face_boundary, double max_gap) {
  std::vector<Candidate> candidates;
  const auto faces = mesh.boundaries.find(face_boundary);
  if (faces == mesh.boundaries.end()) return candidates;
  const BoundaryNodeGeometry nodes = boundary_geometry(mesh, node_boundary);
  const BoundaryNodeGeometry face_nodes = boundary_geometry(mesh, face_boundary);
  std::map<int, Eigen::Vector3d> vertex_normal;
  for (size_t k = 0; k < face_nodes.nodes.size(); ++k) vertex_normal[face_nodes.nodes[k]] = face_nodes.normals[k];
  for (size_t k = 0; k < nodes.nodes.size(); ++k) {
    const int node = nodes.nodes[k];
    const Eigen::Vector3d& x = mesh.nodes[node];
    ClosestFace hit = closest_face(mesh.nodes, faces->second, mesh.dim, x);
    if (hit.face < 0) continue;
    // The partner point: where the common normal through the node meets the other side.
    if (const auto along = project_along_common_normal(mesh, faces->second, vertex_normal, x, nodes.normals[k], hit)) {
      hit.projection = *along;
      hit.face = along->face;
    }
    const BoundaryFace& face = faces->second[hit.face];
    Candidate candidate;
    candidate.node = node;
    candidate.face = hit.face;
    candidate.tributary = nodes.tributary[k];
    if (hit.projection.vertex >= 0) {
      const int vertex = face.nodes[hit.projection.vertex];
      candidate.n_face_nodes = 1;
      candidate.face_nodes = {vertex};
      candidate.weights = {1.0};
      candidate.normal = vertex_normal.at(vertex);
      candidate.gap = (x - mesh.nodes[vertex]).dot(candidate.normal);
    } else {
      candidate.n_face_nodes = face.n_nodes;
      candidate.face_nodes.assign(face.nodes.begin(), face.nodes.begin() + face.n_nodes);
      candidate.weights.assign(hit.projection.weights.begin(), hit.projection.weights.begin() + face.n_nodes);
      candidate.normal = hit.projection.normal;
      candidate.gap = (x - hit.projection.point).dot(candidate.normal);
    }
    Eigen::Vector3d face_normal = Eigen::Vector3d::Zero();  // smoothed, as the projection used it
    for (int j = 0; j < candidate.n_face_nodes; ++j)
      face_normal += candidate.weights[j] * vertex_normal.at(candidate.face_nodes[j]);
    candidate.common_normal = (face_normal.normalized() - nodes.normals[k]).normalized();
    // Facing as for an obstacle: the node's outward normal points against the face's.
    const bool facing = nodes.normals[k].dot(candidate.normal) < -1e-9;
    if (facing && candidate.gap <= max_gap) candidates.push_back(candidate);
  }
  return candidates;
}

}  // namespace contactqp::detail
