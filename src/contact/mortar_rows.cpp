// Mortar rows between two bodies (docs/bodies.md, "Mortar rows"). A node-to-face row ties one
// node to one point of the other side; with meshes that do not match, the forces such rows
// carry scatter from node to node about the true pressure (in 3D by several per cent, a scatter
// that does not fall as the mesh is refined: the rows do not pass the contact patch test).
// A mortar row ties the node's share of its side to the part of the other side that share
// overlaps: with the dual basis ψ_i of the node side (∫ψ_i N_k = δ_ik D_i), the weighted gap
// ∫ψ_i g dA becomes, for the displacements, n_iᵀ(D_i u_i − Σ_j M_ij u_j) with
// M_ij = ∫ψ_i N_j(y(x)) dA, y(x) the closest point of the other side. Divided by D_i this is a
// node-to-face row whose weights M_ij / D_i spread over every face the share overlaps, and
// λ_i / D_i is the pressure. A uniform pressure passes through such rows exactly, up to the
// quadrature of M (its integrand has kinks where the other side's faces meet: integrated by
// many points over each face, not segment by segment).
//
// The node side's displacement is taken linear on each face, or on the four 3-node triangles
// (two segments in 2D) of a quadratic face between its nodes: the dual basis of a 6-node face
// does not exist with positive D_i at its vertices (∫N_i = 0 there), and of its linear pieces
// it does (Puso, Laursen and Solberg's treatment of quadratic faces). A node whose share is
// not wholly over the other side keeps its node-to-face row.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "contact.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp::detail {
namespace {

// A linear piece of a node-side face: its nodes and their reference coordinates on the face.
struct LinearPiece {
  int n = 0;  // 2 (a segment, 2D) or 3 (a triangle, 3D)
  int node[3] = {-1, -1, -1};
  Eigen::Vector2d at[3] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
};

std::vector<LinearPiece> pieces_of(const BoundaryFace& face, int dim) {
  const auto& v = face.nodes;
  auto piece = [&](std::initializer_list<int> local) {
    LinearPiece p;
    for (int k : local) {
      p.node[p.n] = v[k];
      p.at[p.n] = dim == 2 ? Eigen::Vector2d(k == 0 ? 0.0 : (k == 1 ? 1.0 : 0.5), 0.0) : reference_node(k);
      ++p.n;
    }
    return p;
  };
  if (dim == 2)
    return face.n_nodes == 3 ? std::vector<LinearPiece>{piece({0, 2}), piece({2, 1})} : std::vector{piece({0, 1})};
  if (face.n_nodes == 3) return {piece({0, 1, 2})};
  return {piece({0, 3, 5}), piece({1, 4, 3}), piece({2, 5, 4}), piece({3, 4, 5})};
}

// A quadrature point of a piece: its barycentric coordinates on the piece and its share of the
// piece's reference measure (the shares sum to 1).
struct LinearPiecePoint {
  double L[3];
  double share;
};

// 2D: the segment cut into 8, two Gauss points each (degree 3). 3D: the triangle cut into 16,
// six points each (Dunavant's degree-4 rule). Exact for ψ_i N_k on the piece (degree 3 on a
// quadratic face); the integrand of M has kinks where the other side's faces meet, which the
// many points integrate to a small fraction of D_i (the patch test, docs/bodies.md).
const std::vector<LinearPiecePoint>& piece_rule(int dim) {
  static const std::vector<LinearPiecePoint> segment = [] {
    std::vector<LinearPiecePoint> out;
    const int n = 8;
    const double gauss = 0.5 / std::sqrt(3.0);
    for (int i = 0; i < n; ++i)
      for (double offset : {0.5 - gauss, 0.5 + gauss}) {
        const double t = (i + offset) / n;
        out.push_back({{1 - t, t, 0}, 0.5 / n});
      }
    return out;
  }();
  static const std::vector<LinearPiecePoint> triangle = [] {
    std::vector<LinearPiecePoint> out;
    const int n = 4;
    const QuadraturePoint* rule = nullptr;
    const int points = triangle_rule(2, rule);  // weights sum to ½
    auto add = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
      for (int k = 0; k < points; ++k) {
        const double w1 = rule[k].xi, w2 = rule[k].eta, w0 = 1 - w1 - w2;
        const Eigen::Vector2d p = (w0 * a + w1 * b + w2 * c) / n;  // (s, r) on the piece
        out.push_back({{1 - p[0] - p[1], p[0], p[1]}, 2 * rule[k].weight / (n * n)});
      }
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        add({double(i), double(j)}, {double(i + 1), double(j)}, {double(i), double(j + 1)});
        if (i + j + 2 <= n) add({double(i + 1), double(j)}, {double(i + 1), double(j + 1)}, {double(i), double(j + 1)});
      }
    return out;
  }();
  return dim == 2 ? segment : triangle;
}

// The face at reference coordinates `at`: its point, its measure per reference measure
// (|dx/dt| in 2D, |∂x/∂ξ × ∂x/∂η| in 3D) and its own shape functions' values there.
struct ShareFacePoint {
  Eigen::Vector3d x;
  double measure = 0;
  Eigen::VectorXd N;
};
ShareFacePoint face_point(const Mesh& mesh, const BoundaryFace& face, const Eigen::Vector2d& at) {
  const auto& x = mesh.nodes;
  const auto& v = face.nodes;
  ShareFacePoint out;
  if (mesh.dim == 2) {
    const Eigen::Vector3d* m = face.n_nodes == 3 ? &x[v[2]] : nullptr;
    const EdgePoint e = edge_point(at[0], x[v[0]], x[v[1]], m);
    out.x = e.N[0] * x[v[0]] + e.N[1] * x[v[1]];
    if (m) out.x += e.N[2] * *m;
    out.measure = e.dx.norm();
    out.N = Eigen::Vector3d(e.N[0], e.N[1], e.N[2]).head(face.n_nodes);
    return out;
  }
  const int order = face.n_nodes == 6 ? 2 : 1;
  out.N = shape_values(order, at[0], at[1]);
  const Eigen::Matrix<double, 2, Eigen::Dynamic> dN = shape_gradients(order, at[0], at[1]);
  Eigen::Vector3d d0 = Eigen::Vector3d::Zero(), d1 = d0;
  out.x.setZero();
  for (int k = 0; k < face.n_nodes; ++k) {
    out.x += out.N[k] * x[v[k]];
    d0 += dN(0, k) * x[v[k]];
    d1 += dN(1, k) * x[v[k]];
  }
  out.measure = d0.cross(d1).norm();
  return out;
}

struct FaceBox {
  Eigen::Vector3d lo, hi;
};
FaceBox box_of(const Mesh& mesh, const BoundaryFace& face) {
  FaceBox b{mesh.nodes[face.nodes[0]], mesh.nodes[face.nodes[0]]};
  for (int k = 1; k < face.n_nodes; ++k) {
    b.lo = b.lo.cwiseMin(mesh.nodes[face.nodes[k]]);
    b.hi = b.hi.cwiseMax(mesh.nodes[face.nodes[k]]);
  }
  return b;
}

// What one node's share gathers: S_i = ∫ψ_i (= ∫L_i over its linear pieces: its tributary),
// the row's terms (M_ij on the other side's nodes, −D_ik = −∫ψ_i N_k on its own side's: on a
// linear face D_ik = δ_ik S_i, on a quadratic one not), and the L_i-weighted mean of the other
// side's normal.
struct MortarShare {
  double dual = 0;
  std::map<int, double> weight;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool off = false;  // a point of the share had no face of the other side beneath it
};

}  // namespace

void make_mortar_rows(const Mesh& mesh, const std::string& node_boundary, const std::string& face_boundary,
                      std::vector<Candidate>& candidates) {
  const auto node_faces = mesh.boundaries.find(node_boundary);
  const auto other_faces = mesh.boundaries.find(face_boundary);
  if (candidates.empty() || node_faces == mesh.boundaries.end() || other_faces == mesh.boundaries.end()) return;
  const int dim = mesh.dim;
  std::map<int, MortarShare> shares;  // candidate node → its share
  double largest_gap = 0;
  for (const Candidate& c : candidates) {
    shares[c.node];
    largest_gap = std::max(largest_gap, std::abs(c.gap));
  }
  std::vector<FaceBox> other_boxes;
  for (const BoundaryFace& face : other_faces->second) other_boxes.push_back(box_of(mesh, face));
  const std::vector<LinearPiecePoint>& rule = piece_rule(dim);
  std::vector<BoundaryFace> near;  // the other side's faces near one face of the node side
  std::vector<int> near_index;
  for (const BoundaryFace& face : node_faces->second) {
    bool any = false;
    for (int k = 0; k < face.n_nodes; ++k) any = any || shares.count(face.nodes[k]);
    if (!any) continue;
    // The other side's faces that a closest point of this face can lie on: within the largest
    // gap of it (and its size, for the curvature between its nodes), nearest first, so that
    // closest_face() passes over the rest by their boxes.
    const FaceBox box = box_of(mesh, face);
    const double margin = (box.hi - box.lo).norm() + largest_gap;
    const Eigen::Vector3d centre = 0.5 * (box.lo + box.hi);
    std::vector<std::pair<double, int>> order;
    for (std::size_t f = 0; f < other_boxes.size(); ++f)
      if (((other_boxes[f].lo - box.hi).array() <= margin).all() &&
          ((box.lo - other_boxes[f].hi).array() <= margin).all())
        order.emplace_back((0.5 * (other_boxes[f].lo + other_boxes[f].hi) - centre).norm(), static_cast<int>(f));
    std::sort(order.begin(), order.end());
    near.clear();
    near_index.clear();
    for (const auto& [distance, f] : order) {
      near.push_back(other_faces->second[f]);
      near_index.push_back(f);
    }
    const double reference_measure = dim == 2 ? 1.0 : 0.5;  // of the whole face
    const std::vector<LinearPiece> pieces = pieces_of(face, dim);
    const double piece_measure = reference_measure / static_cast<double>(pieces.size());
    for (const LinearPiece& piece : pieces) {
      for (const LinearPiecePoint& q : rule) {
        Eigen::Vector2d at = Eigen::Vector2d::Zero();
        for (int k = 0; k < piece.n; ++k) at += q.L[k] * piece.at[k];
        const ShareFacePoint point = face_point(mesh, face, at);
        const Eigen::Vector3d& x = point.x;
        const double w = q.share * piece_measure * point.measure;
        const ClosestFace hit = near.empty() ? ClosestFace{} : closest_face(mesh.nodes, near, dim, x);
        bool off = hit.face < 0;
        if (!off) {
          // Beyond the other side's edge the closest point is on that edge, and the offset
          // leans along the side instead of across it.
          const Eigen::Vector3d offset = x - hit.projection.point;
          const Eigen::Vector3d& n = hit.projection.normal;
          const FaceBox& b = other_boxes[static_cast<std::size_t>(near_index[static_cast<std::size_t>(hit.face)])];
          off = (offset - offset.dot(n) * n).norm() > 0.25 * (b.hi - b.lo).norm();
        }
        for (int k = 0; k < piece.n; ++k) {
          const auto share = shares.find(piece.node[k]);
          if (share == shares.end()) continue;
          MortarShare& s = share->second;
          const double L = q.L[k], psi = dim == 2 ? 3 * L - 1 : 4 * L - 1;
          if (off) {
            s.off = true;
            continue;
          }
          s.dual += w * psi;
          s.normal += w * L * hit.projection.normal;
          const BoundaryFace& other = near[static_cast<std::size_t>(hit.face)];
          for (int j = 0; j < other.n_nodes; ++j) s.weight[other.nodes[j]] += w * psi * hit.projection.weights[j];
          for (int j = 0; j < face.n_nodes; ++j) s.weight[face.nodes[j]] -= w * psi * point.N[j];
        }
      }
    }
  }
  for (Candidate& c : candidates) {
    MortarShare& s = shares.at(c.node);
    if (s.off || !(s.dual > 0) || !(s.normal.norm() > 0)) continue;  // keeps node-to-face
    // Divided by S_i, the row's own term is 1 and λ_i the force it carries: the node's own
    // D_ii / S_i, short of 1 on a quadratic face, is made up by the node in the list.
    s.weight[c.node] += s.dual;
    double largest = 0;
    for (const auto& [node, m] : s.weight) largest = std::max(largest, std::abs(m));
    c.face_nodes.clear();
    c.weights.clear();
    for (const auto& [node, m] : s.weight)
      if (std::abs(m) > 1e-12 * largest) {
        c.face_nodes.push_back(node);
        c.weights.push_back(m / s.dual);
      }
    c.n_face_nodes = static_cast<int>(c.face_nodes.size());
    c.normal = s.normal.normalized();
    Eigen::Vector3d partner = Eigen::Vector3d::Zero();
    for (int j = 0; j < c.n_face_nodes; ++j) partner += c.weights[j] * mesh.nodes[c.face_nodes[j]];
    c.gap = (mesh.nodes[c.node] - partner).dot(c.normal);
    c.tributary = s.dual;
  }
}

}  // namespace contactqp::detail
