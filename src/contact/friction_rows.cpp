// The tangential rows of friction (friction.hpp): for every contact row, dim − 1 unit tangents
// orthogonal to its normal, in the obstacle's or the pair's frame, and the row's bound — Tresca's
// s·w_i or Coulomb's μ_i. Quasi-static steps: the offset is each row's tangential position at the
// end of the last step, with the prescribed displacements' part of this step moved into it (as
// g holds theirs), so that T u − offset is the step's slip.
#include <Eigen/Geometry>
#include <cmath>
#include <set>

#include "contact.hpp"

namespace contactqp::detail {
namespace {

// The friction of an obstacle row of a scene with bodies: the boundary entry its node is on.
const FrictionSpec* entry_friction(const Model& model, const Candidate& c) {
  for (const ObstacleContactSpec& entry : model.scene.obstacle_contacts) {
    if (entry.body != c.body || !entry.friction) continue;
    const std::string boundary = model.bodies[entry.body].name + "." + entry.boundary;
    for (int node : boundary_nodes(model.mesh, boundary))
      if (node == c.node) return &*entry.friction;
  }
  return nullptr;
}

}  // namespace

const FrictionSpec* friction_of(const Model& model, const Candidate& c) {
  const Scene& scene = model.scene;
  if (c.pair >= 0) return scene.pairs[c.pair].friction ? &*scene.pairs[c.pair].friction : nullptr;
  if (scene.contact.friction) return &*scene.contact.friction;
  if (scene.obstacles[c.obstacle].friction) return &*scene.obstacles[c.obstacle].friction;
  return model.bodies.empty() ? nullptr : entry_friction(model, c);
}

Eigen::Vector3d row_normal(const Model& model, const Candidate& c) {
  // A pair's gap closes along the common normal: two identical spheres pressed together meet
  // along z while each side's normal leans by r/R, and tangents across the face normal counted
  // a share of the approach as slip (a slipping rim under the press alone, where Mindlin has none).
  if (c.pair >= 0) return c.common_normal.squaredNorm() > 0 ? c.common_normal : c.normal;
  return project(model.scene.obstacles[c.obstacle], model.mesh.nodes[c.node]).normal;
}

namespace {

// How far from the row's plane a prescribed direction may lean and still be taken as a
// tangent: a symmetry plane's normal leans off the mesh's normal at a node on the plane by the
// discretisation only (the normal averages the faces on one side of it), a few degrees at most.
constexpr double kTangentialLean = 0.1;

// The node's prescribed directions (global axes) that lie nearly in the plane across n.
std::vector<Eigen::Vector3d> prescribed_tangents(const Model& model, int node, const Eigen::Vector3d& n) {
  const int dim = model.dim;
  const Eigen::MatrixXd frame = dof_frame(model, node);
  std::vector<Eigen::Vector3d> along;
  for (int k = 0; k < dim; ++k) {
    if (model.free_index[dim * node + k] >= 0) continue;
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e.head(dim) = frame.col(k);
    if (std::abs(e.dot(n)) <= kTangentialLean) along.push_back(e);
  }
  return along;
}

}  // namespace

std::vector<Eigen::Vector3d> row_tangents(const Model& model, const Candidate& c) {
  const Eigen::Vector3d n = row_normal(model, c);
  // A node on a symmetry plane cannot move across it: that direction is a tangent, so that,
  // where the partner lies on the plane too, the row along it has entries on prescribed DOFs
  // only and drops out of T exactly (the solvers keep a zero row's λ_T at 0). A tangent of the
  // mesh's normal, which leans off the plane, left a tiny row that is a multiple of the normal
  // row on the free DOFs: a sticking node's Newton system was singular, and active_set ran
  // gradient steps only (scenes/mindlin-spheres.json's plane y = 0, Coulomb's press step).
  const std::vector<Eigen::Vector3d> prescribed = prescribed_tangents(model, c.node, n);
  if (model.dim == 2) {
    const Eigen::Vector3d t(n.y(), -n.x(), 0.0);
    if (prescribed.empty()) return {t};
    return {prescribed.front().dot(t) < 0 ? Eigen::Vector3d(-prescribed.front()) : prescribed.front()};
  }
  if (prescribed.size() >= 2) return {prescribed[0], prescribed[1]};  // on two planes: no free slip
  if (prescribed.size() == 1) {
    const Eigen::Vector3d& t2 = prescribed.front();
    return {t2.cross(n).normalized(), t2};  // t1 ⊥ n and t2; n × t1 is t2 up to its lean
  }
  // The scene's own x axis (turned by its transform) across n; its y axis where n is near x.
  Eigen::Vector3d t1 = model.rotation.col(0) - model.rotation.col(0).dot(n) * n;
  if (t1.norm() < 0.5) t1 = model.rotation.col(1) - model.rotation.col(1).dot(n) * n;
  t1.normalize();
  return {t1, n.cross(t1)};
}

std::vector<TangentialRow> tangential_rows(const Model& model) {
  const int dim = model.dim;
  std::vector<TangentialRow> rows;
  for (const Candidate& c : model.candidates) {
    for (const Eigen::Vector3d& t : row_tangents(model, c)) {
      TangentialRow row;
      // t_kᵀ u_node in the node's DOF frame: the coefficients of its components are Fᵀ t.
      auto add = [&](int node, double scale) {
        const Eigen::VectorXd along = dof_frame(model, node).transpose() * t.head(dim);
        for (int k = 0; k < dim; ++k)
          if (along[k] != 0.0 && scale != 0.0) row.entries.emplace_back(dim * node + k, scale * along[k]);
      };
      add(c.node, 1.0);
      for (int j = 0; j < c.n_face_nodes; ++j) add(c.face_nodes[j], -c.weights[j]);
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

Eigen::VectorXd tangential_positions(const Model& model, const Eigen::VectorXd& u) {
  const std::vector<TangentialRow> rows = tangential_rows(model);
  Eigen::VectorXd position = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [dof, value] : rows[r].entries) {
      if (model.free_index[dof] < 0) position[r] += value * model.prescribed[dof];
      const double coefficient = value;  // C++17 lambdas cannot capture a structured binding
      for_each_column(model, dof, [&](int column, double w) { position[r] += coefficient * w * u[column]; });
    }
  return position;
}

void set_friction_offset(const Model& model, QuadraticProgram& qp, const Eigen::VectorXd& previous) {
  const std::vector<TangentialRow> rows = tangential_rows(model);
  qp.friction.offset = previous;
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [dof, value] : rows[r].entries)
      if (model.free_index[dof] < 0) qp.friction.offset[r] -= value * model.prescribed[dof];
}

void add_friction_rows(const Model& model, QuadraticProgram& qp) {
  const FrictionLaw law = model.scene.friction_law();
  if (law == FrictionLaw::None) return;
  const int dim = model.dim, m = static_cast<int>(model.candidates.size());
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  FrictionBlock& block = qp.friction;
  block.law = law;
  block.n_directions = dim - 1;
  const std::vector<TangentialRow> rows = tangential_rows(model);
  std::vector<Eigen::Triplet<double>> entries;
  for (size_t r = 0; r < rows.size(); ++r)
    for (const auto& [dof, value] : rows[r].entries) {
      const double coefficient = value;  // C++17 lambdas cannot capture a structured binding
      for_each_column(model, dof, [&](int column, double w) {
        entries.emplace_back(static_cast<int>(r), column, w * coefficient);
      });
    }
  block.T.resize(static_cast<Eigen::Index>(rows.size()), qp.n_dofs());
  block.T.setFromTriplets(entries.begin(), entries.end());
  block.T.makeCompressed();
  Eigen::VectorXd& bound = law == FrictionLaw::Tresca ? block.threshold : block.coefficient;
  bound = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < m; ++i) {
    const Candidate& c = model.candidates[i];
    if (const FrictionSpec* friction = friction_of(model, c))
      bound[i] = law == FrictionLaw::Tresca ? friction->threshold * c.tributary * thickness : friction->coefficient;
  }
  set_friction_offset(model, qp, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size())));
}

}  // namespace contactqp::detail
