// Is the body held against rigid motion? Decided from the prescribed DOFs alone, before K is
// assembled or factorised: a body that can still translate or rotate freely has a singular K,
// whose factorisation either fails or — worse — succeeds on round-off and returns a
// displacement with an arbitrary rigid part.
//
// In 2D the rigid motions of a connected body are the span of t_x = (1, 0), t_y = (0, 1) and
// the rotation r(x) = (−(y − y_c), x − x_c)/ℓ (centred at the part's centroid and scaled by its
// extent ℓ, so the three columns are of the same size). A prescribed component c at node i,
// along the direction d (its DOF frame's column c), holds the motions m with d·m(x_i) ≠ 0:
// the part is held exactly when the rows [d·t_x, d·t_y, d·r(x_i)] over its prescribed DOFs
// have rank 3. The null space of those rows is what moves freely. In 3D the same with six
// motions: translations t_x, t_y, t_z and rotations ω × (x − x_c)/ℓ, whose row is
// [d, ((x − x_c) × d)/ℓ].
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
#include "model_parts.hpp"

namespace contactqp::detail {
namespace {

// A restraint this weak relative to the strongest (an eigenvalue of the 3 × 3 normal matrix)
// is none: it comes from round-off, not from a prescribed displacement.
constexpr double kNullTolerance = 1e-10;

int find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The connected parts of the mesh: part[node], numbered 0, 1, ... in order of first node.
std::vector<int> connected_parts(const Mesh& mesh, int& n_parts) {
  std::vector<int> parent(mesh.n_nodes());
  std::iota(parent.begin(), parent.end(), 0);
  const int npe = mesh.nodes_per_element();
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int i = 1; i < npe; ++i) parent[find(parent, v[i])] = find(parent, v[0]);
  }
  std::vector<int> part(mesh.n_nodes(), -1), label(mesh.n_nodes(), -1);
  n_parts = 0;
  for (int node = 0; node < mesh.n_nodes(); ++node) {
    const int root = find(parent, node);
    if (label[root] < 0) label[root] = n_parts++;
    part[node] = label[root];
  }
  return part;
}

// x for a message: six digits, and 0 for round-off (below 1e-9 of `scale`).
std::string cleaned_number(double x, double scale) { return number(std::abs(x) <= 1e-9 * scale ? 0.0 : x); }

std::string direction_name(const Eigen::Vector2d& d) {
  if (std::abs(d.y()) <= 1e-9 * std::abs(d.x())) return "x";
  if (std::abs(d.x()) <= 1e-9 * std::abs(d.y())) return "y";
  const Eigen::Vector2d unit = d.normalized();
  return "along (" + cleaned_number(unit.x(), 1) + ", " + cleaned_number(unit.y(), 1) + ")";
}

// The free motions, in words, from a basis of the null space (columns (a, b, c) of
// a·t_x + b·t_y + c·r), and what would hold them.
struct FreeMotions {
  std::string what, fix;
};

FreeMotions describe(const Eigen::MatrixXd& null, const Eigen::Vector2d& centre, double extent) {
  const int k = static_cast<int>(null.cols());
  // a t_x + b t_y + c r(x) vanishes at x − x_c = −bℓ/c, y − y_c = aℓ/c. With a free
  // translation along d too, a rotation about any point of the line through it across d is
  // free (adding s·d moves the centre by s/c across d): name the one nearest the centroid.
  auto rotation_centre = [&](const Eigen::Vector3d& v, const Eigen::Vector2d& d) {
    Eigen::Vector2d point = centre + Eigen::Vector2d(-v[1], v[0]) * extent / v[2];
    if (d.norm() > 0) {
      const Eigen::Vector2d across = Eigen::Vector2d(-d.y(), d.x()).normalized();
      point += (centre - point).dot(across) * across;
    }
    return "rotation about (" + cleaned_number(point.x(), extent) + ", " + cleaned_number(point.y(), extent) + ")";
  };
  const std::string hold_x =
      "prescribe u_x on some boundary (e.g. \"value\": [0, ...] instead of [null, ...]), or model half of a "
      "symmetric body with \"body.symmetry\": true";
  const std::string hold_any =
      "add a displacement load that prescribes both components (\"value\": [ux, uy]) on a boundary";
  if (k == 3) return {"translations in x and y and rotation", hold_any};
  if (k == 2) {
    // The translations in the null space: the vectors with c = 0, a plane through two 3-vectors.
    const Eigen::Vector3d normal = Eigen::Vector3d(null.col(0)).cross(Eigen::Vector3d(null.col(1))).normalized();
    if (std::abs(normal[0]) < 1e-9 && std::abs(normal[1]) < 1e-9) return {"translations in x and y", hold_any};
    const Eigen::Vector3d translation = normal.cross(Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d other = normal.cross(translation);  // in the null space, c ≠ 0
    const std::string name = direction_name(translation.head<2>());
    return {"translation in " + name + " and " + rotation_centre(other, translation.head<2>()),
            name == "x" ? hold_x : "prescribe displacements at two or more points that block them, e.g. " + hold_any};
  }
  const Eigen::Vector3d v = null.col(0);
  if (std::abs(v[2]) <= 1e-9 * v.head<2>().norm()) {
    const std::string name = direction_name(v.head<2>());
    if (name == "x") return {"translation in x", hold_x};
    if (name == "y") return {"translation in y", "prescribe u_y on some boundary"};
    return {"translation " + name, hold_any};
  }
  return {rotation_centre(v, Eigen::Vector2d::Zero()),
          "prescribe a displacement at a second point, away from that centre"};
}

std::string vector_text(const Eigen::Vector3d& d) {
  const Eigen::Vector3d unit = d.normalized();
  for (int c = 0; c < 3; ++c)
    if (std::abs(std::abs(unit[c]) - 1) < 1e-9) return std::string(1, "xyz"[c]);
  return "(" + cleaned_number(unit.x(), 1) + ", " + cleaned_number(unit.y(), 1) + ", " + cleaned_number(unit.z(), 1) +
         ")";
}

// The free motions of a 3D part, in words, from a basis of the null space (columns (t, ω) of
// t + ω × (x − x_c)/ℓ): the translations it spans, then the rotations (about the axis through
// the point that makes the motion a pure rotation where it is one).
std::string describe_3d(const Eigen::MatrixXd& null, const Eigen::Vector3d& centre, double extent) {
  std::string text;
  for (int k = 0; k < null.cols(); ++k) {
    const Eigen::Vector3d t = null.col(k).head<3>(), w = null.col(k).tail<3>() / extent;
    std::string motion;
    if (w.norm() * extent <= 1e-9 * t.norm()) {
      motion = "translation along " + vector_text(t);
    } else {
      // t + w × y = w × (y − p) for p = (w × t)/|w|² when t ⟂ w: a rotation about the axis through x_c + p.
      const Eigen::Vector3d p = centre + w.cross(t) / w.squaredNorm();
      motion = "rotation about an axis along " + vector_text(w) + " through (" + cleaned_number(p.x(), extent) + ", " +
               cleaned_number(p.y(), extent) + ", " + cleaned_number(p.z(), extent) + ")";
    }
    text += (text.empty() ? "" : ", ") + motion;
  }
  return text;
}

RigidFreedom rigid_freedom_3d(const Model& model) {
  const Mesh& mesh = model.mesh;
  RigidFreedom freedom;
  int n_parts = 0;
  freedom.part = connected_parts(mesh, n_parts);
  const std::vector<int>& part = freedom.part;
  freedom.parts.assign(n_parts, PartFreedom{});
  std::vector<double> volume(n_parts, 0.0);
  for (int node = 0; node < mesh.n_nodes(); ++node)
    if (freedom.parts[part[node]].first_node < 0) freedom.parts[part[node]].first_node = node;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    const double V = std::abs(element_measure(mesh, e));
    freedom.parts[part[v[0]]].centre +=
        V * (mesh.nodes[v[0]] + mesh.nodes[v[1]] + mesh.nodes[v[2]] + mesh.nodes[v[3]]) / 4.0;
    volume[part[v[0]]] += V;
  }
  for (int p = 0; p < n_parts; ++p)
    if (volume[p] > 0) freedom.parts[p].centre /= volume[p];
  std::vector<double> extent(n_parts, 0.0);
  for (int node = 0; node < mesh.n_nodes(); ++node)
    extent[part[node]] = std::max(extent[part[node]], (mesh.nodes[node] - freedom.parts[part[node]].centre).norm());
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  std::vector<Matrix6d> normal(n_parts, Matrix6d::Zero());
  for (int node = 0; node < mesh.n_nodes(); ++node) {
    const int p = part[node];
    const double l = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::Vector3d x = mesh.nodes[node] - freedom.parts[p].centre;
    const Eigen::MatrixXd frame = dof_frame(model, node);
    for (int c = 0; c < 3; ++c) {
      if (model.free_index[3 * node + c] >= 0) continue;
      const Eigen::Vector3d d = frame.col(c);
      Eigen::Matrix<double, 6, 1> row;
      row << d, x.cross(d) / l;
      normal[p] += row * row.transpose();
    }
  }
  // A rigid surface moves its nodes alike along its component: a motion that moves two of them
  // differently along it is held (a rotation that would tilt a surface pushed by a force),
  // unless the surface turns with it (a moment about that axis: only the other axes are held).
  for (const RigidSurface& surface : model.rigid_surfaces) {
    const int first = surface.nodes.front(), p = part[first];
    const double l = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::Vector3d d = Eigen::Vector3d(dof_frame(model, first).col(surface.component));
    const Eigen::Vector3d x0 = mesh.nodes[first] - freedom.parts[p].centre;
    Eigen::Matrix3d held = Eigen::Matrix3d::Identity();
    for (const RigidRotation& turn : model.rigid_rotations)
      if (turn.load == surface.load) held -= model.rotation.col(turn.axis) * model.rotation.col(turn.axis).transpose();
    for (int node : surface.nodes) {
      if (part[node] != p) continue;  // a surface over two parts ties them: each part's own rows suffice
      const Eigen::Vector3d x = mesh.nodes[node] - freedom.parts[p].centre;
      Eigen::Matrix<double, 6, 1> row;
      row << Eigen::Vector3d::Zero(), held * (x - x0).cross(d) / l;
      normal[p] += row * row.transpose();
    }
  }
  for (int p = 0; p < n_parts; ++p) {
    freedom.parts[p].extent = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::SelfAdjointEigenSolver<Matrix6d> eigen(normal[p]);
    const Eigen::Matrix<double, 6, 1> values = eigen.eigenvalues();  // ascending
    int k = 0;
    while (k < 6 && !(values[k] > kNullTolerance * values[5])) ++k;
    freedom.parts[p].null = eigen.eigenvectors().leftCols(k);
  }
  return freedom;
}

RigidFreedom rigid_freedom_2d(const Model& model);

}  // namespace

// Today's refusal of part p, free to move along the motions `null` (columns of rigid coordinates).
[[noreturn]] void refuse_free_part(const Model& model, const RigidFreedom& freedom, int p, const Eigen::MatrixXd& null,
                                   const std::string& why) {
  const Mesh& mesh = model.mesh;
  const PartFreedom& part = freedom.parts[p];
  const int k = static_cast<int>(null.cols());
  // "the body" when the part is all of it; with several bodies the field names the body's loads.
  std::string field = "load";
  bool one = freedom.parts.size() == 1;
  bool symmetric = model.scene.body.symmetry;
  if (!model.bodies.empty()) {
    const int b = model.body_of_node(part.first_node);
    const ModelBody& body = model.bodies[static_cast<size_t>(b)];
    field = "bodies[" + std::to_string(b) + "].load";
    symmetric = body.scene.body.symmetry;
    int parts_of_body = 0;
    for (const PartFreedom& other : freedom.parts)
      parts_of_body += other.first_node >= body.first_node && other.first_node < body.first_node + body.n_nodes;
    one = parts_of_body == 1;
  }
  if (model.dim == 3) {
    const std::string which = one ? "the body"
                                  : "the part of the body with node " + std::to_string(part.first_node) + " at " +
                                        format_point(mesh.nodes[part.first_node], 3);
    throw InputError(field,
                     "leaves " + which + " free to move rigidly (" + describe_3d(null, part.centre, part.extent) +
                         "): " + why + "; prescribe displacements that block " +
                         (k == 6 ? "every motion (e.g. \"value\": [ux, uy, uz] on a face)" : "these motions") +
                         (symmetric ? "" : ", or model a symmetric body's quarter with \"body.symmetry\": true"));
  }
  const FreeMotions free = describe(null, part.centre.head<2>(), part.extent);
  const std::string which = one ? "the body"
                                : "the part of the body with node " + std::to_string(part.first_node) + " at (" +
                                      cleaned_number(mesh.nodes[part.first_node].x(), part.extent) + ", " +
                                      cleaned_number(mesh.nodes[part.first_node].y(), part.extent) + ")";
  throw InputError(field, "leaves " + which + " free to move rigidly (" + free.what + "): " + why + "; " + free.fix);
}

Eigen::Vector3d rigid_motion_at(const PartFreedom& part, const Eigen::VectorXd& rigid, const Eigen::Vector3d& x,
                                int dim) {
  const Eigen::Vector3d r = (x - part.centre) / part.extent;
  if (dim == 3) return rigid.head<3>() + Eigen::Vector3d(rigid.tail<3>()).cross(r);
  return Eigen::Vector3d(rigid[0] - rigid[2] * r.y(), rigid[1] + rigid[2] * r.x(), 0.0);
}

std::string describe_motion(const Model& model, const PartFreedom& part, const Eigen::VectorXd& rigid) {
  const double rotation = model.dim == 3 ? rigid.tail<3>().norm() : std::abs(rigid[2]);
  const Eigen::Vector3d t = model.dim == 3 ? Eigen::Vector3d(rigid.head<3>()) : Eigen::Vector3d(rigid[0], rigid[1], 0);
  if (rotation <= 1e-9 * t.norm()) {
    // A translation: its signed direction, "+z" along an axis.
    const Eigen::Vector3d unit = t.normalized();
    for (int c = 0; c < model.dim; ++c)
      if (std::abs(std::abs(unit[c]) - 1) < 1e-9) return std::string("along ") + (unit[c] > 0 ? "+" : "-") + "xyz"[c];
    return "along (" + cleaned_number(unit.x(), 1) + ", " + cleaned_number(unit.y(), 1) +
           (model.dim == 3 ? ", " + cleaned_number(unit.z(), 1) : std::string()) + ")";
  }
  if (model.dim == 3) return "by " + describe_3d(rigid, part.centre, part.extent);
  return "by " + describe(rigid, part.centre.head<2>(), part.extent).what +
         (rigid[2] > 0 ? ", anticlockwise" : ", clockwise");
}

RigidFreedom rigid_freedom(const Model& model) {
  return model.dim == 3 ? rigid_freedom_3d(model) : rigid_freedom_2d(model);
}

void check_rigid_motions(const Model& model) {
  const RigidFreedom freedom = rigid_freedom(model);
  for (size_t p = 0; p < freedom.parts.size(); ++p)
    if (freedom.parts[p].null.cols() > 0)
      refuse_free_part(model, freedom, static_cast<int>(p), freedom.parts[p].null, kNothingHolds);
}

namespace {

RigidFreedom rigid_freedom_2d(const Model& model) {
  const Mesh& mesh = model.mesh;
  RigidFreedom freedom;
  int n_parts = 0;
  freedom.part = connected_parts(mesh, n_parts);
  const std::vector<int>& part = freedom.part;
  // Each part's area centroid (exact for a symmetric body, whatever its mesh) and extent.
  std::vector<Eigen::Vector2d> centre(n_parts, Eigen::Vector2d::Zero());
  std::vector<double> area(n_parts, 0.0);
  std::vector<int> first_node(n_parts, -1);
  for (int node = 0; node < mesh.n_nodes(); ++node)
    if (first_node[part[node]] < 0) first_node[part[node]] = node;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    const double a = std::abs(element_area(mesh, e));
    centre[part[v[0]]] +=
        a * (mesh.nodes[v[0]].head<2>() + mesh.nodes[v[1]].head<2>() + mesh.nodes[v[2]].head<2>()) / 3.0;
    area[part[v[0]]] += a;
  }
  std::vector<double> extent(n_parts, 0.0);
  for (int p = 0; p < n_parts; ++p)
    if (area[p] > 0) centre[p] /= area[p];
  for (int node = 0; node < mesh.n_nodes(); ++node)
    extent[part[node]] = std::max(extent[part[node]], (mesh.nodes[node].head<2>() - centre[part[node]]).norm());

  std::vector<Eigen::Matrix3d> normal(n_parts, Eigen::Matrix3d::Zero());
  for (int node = 0; node < mesh.n_nodes(); ++node) {
    const int p = part[node];
    const double l = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::Vector2d x = mesh.nodes[node].head<2>() - centre[p];
    const Eigen::Matrix2d frame = dof_frame(model, node);
    for (int c = 0; c < 2; ++c) {
      if (model.free_index[2 * node + c] >= 0) continue;
      const Eigen::Vector2d d = frame.col(c);
      const Eigen::Vector3d row(d.x(), d.y(), (-d.x() * x.y() + d.y() * x.x()) / l);
      normal[p] += row * row.transpose();
    }
  }
  // A rigid surface moves its nodes alike along its component (as in 3D above), unless it turns.
  for (const RigidSurface& surface : model.rigid_surfaces) {
    const auto turns = [&](const RigidRotation& turn) { return turn.load == surface.load; };
    if (std::any_of(model.rigid_rotations.begin(), model.rigid_rotations.end(), turns)) continue;
    const int first = surface.nodes.front(), p = part[first];
    const double l = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::Vector2d d = dof_frame(model, first).col(surface.component);
    for (int node : surface.nodes) {
      if (part[node] != p) continue;
      const Eigen::Vector2d dx = mesh.nodes[node].head<2>() - mesh.nodes[first].head<2>();
      const Eigen::Vector3d row(0.0, 0.0, (-d.x() * dx.y() + d.y() * dx.x()) / l);
      normal[p] += row * row.transpose();
    }
  }
  freedom.parts.assign(n_parts, PartFreedom{});
  for (int p = 0; p < n_parts; ++p) {
    PartFreedom& out = freedom.parts[p];
    out.first_node = first_node[p];
    out.centre = Eigen::Vector3d(centre[p].x(), centre[p].y(), 0.0);
    out.extent = extent[p] > 0 ? extent[p] : 1.0;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(normal[p]);
    const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
    int k = 0;
    while (k < 3 && !(values[k] > kNullTolerance * values[2])) ++k;
    out.null = eigen.eigenvectors().leftCols(k);
  }
  return freedom;
}

}  // namespace
}  // namespace contactqp::detail
