// A model whose prescribed DOFs leave rigid motions free: allowed when its contact candidates
// can hold them (docs/extremes.md, "Bodies held only by their contacts").
//
// For each connected part with free motions m_1..m_k (rigid_motions.cpp), candidate row r sees
// motion j by G_rj = −n_rᵀ m_j(x_r) (n_r the obstacle normal at its node; a pair's row
// −nᵀ(u_i − Σ N_j u_j) sees the part through whichever of its nodes it holds) and the load drives it
// by F_j = Σ_i f_iᵀ m_j(x_i); a frictional row's tangents t see it by tᵀm_j (the body is then
// held by friction up to μP, which the solve checks). A combination that no row sees (G z = 0)
// can never be stopped:
// if the load drives it (Fᵀz ≠ 0) the scene is refused before any work, with the line
// check_rigid_motions gives; if not (a frictionless ball's sideways translation) it stays a free
// mode, which solve() fixes by its stated choice. Every free motion becomes a column of K's null
// space; whether the contacts do hold the load (or it pulls the body away, and the solve ends
// unbounded) is the solve's to say.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "contact/contact.hpp"
#include "model_parts.hpp"
#include "qp/dense_decompositions.hpp"

namespace contactqp::detail {
namespace {

// The rows of z with G z = 0: an orthonormal basis of G's null space (k × z).
Eigen::MatrixXd unseen_combinations(const Eigen::MatrixXd& G, int k) {
  if (G.rows() == 0) return Eigen::MatrixXd::Identity(k, k);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(G, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  // Rows of unit normals against motions of unit size at most: σ of order √rows; round-off is 1e-12 of it.
  const double largest = sigma.size() ? sigma[0] : 0.0;
  long rank = 0;
  for (long j = 0; j < sigma.size(); ++j)
    if (sigma[j] > 1e-10 * std::max(1.0, largest)) ++rank;
  return svd.matrixV().rightCols(k - rank);
}

// A turning surface's load on the part's motions (F_j = its work on motion j): its moment's,
// and its force's at the centre rather than at the first node, where `scene_force` puts it.
void add_turning_work(const Model& model, const RigidFreedom& freedom, int p, Eigen::VectorXd& F, double& total) {
  const int dim = model.dim;
  const PartFreedom& part = freedom.parts[static_cast<size_t>(p)];
  auto motion = [&](long j, const Eigen::Vector3d& x) { return rigid_motion_at(part, part.null.col(j), x, dim); };
  for (const RigidRotation& turn : model.rigid_rotations) {
    if (freedom.part[turn.nodes.front()] != p) continue;
    const Eigen::Vector3d axis = model.rotation.col(turn.axis);
    const Eigen::Vector3d across = axis.unitOrthogonal(), third = axis.cross(across);
    total += std::abs(turn.moment) / part.extent;
    for (long j = 0; j < F.size(); ++j)  // the angle about the axis: (m(c + b) − m(c))·(axis × b)
      F[j] += turn.moment * (motion(j, turn.centre + across) - motion(j, turn.centre)).dot(third);
  }
  for (const RigidSurface& surface : model.rigid_surfaces) {
    const int first = surface.nodes.front();
    if (freedom.part[first] != p) continue;
    const auto turns = [&](const RigidRotation& turn) { return turn.load == surface.load; };
    const auto turn = std::find_if(model.rigid_rotations.begin(), model.rigid_rotations.end(), turns);
    if (turn == model.rigid_rotations.end()) continue;
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d.head(dim) = dof_frame(model, first).col(surface.component);
    for (long j = 0; j < F.size(); ++j)
      F[j] += rigid_surface_share(model, surface) * d.dot(motion(j, turn->centre) - motion(j, model.mesh.nodes[first]));
  }
}

}  // namespace

Eigen::MatrixXd motions_held_by_contact(Model& model, const std::function<Eigen::VectorXd()>& scene_force) {
  const RigidFreedom freedom = rigid_freedom(model);
  const int dim = model.dim, n_nodes = model.mesh.n_nodes();
  model.free_motions.clear();
  std::vector<Eigen::VectorXd> columns;
  Eigen::VectorXd force;
  for (size_t p = 0; p < freedom.parts.size(); ++p) {
    const PartFreedom& part = freedom.parts[p];
    const int k = static_cast<int>(part.null.cols());
    if (k == 0) continue;
    if (force.size() == 0) force = scene_force();
    auto motion = [&](int j, int node) { return rigid_motion_at(part, part.null.col(j), model.mesh.nodes[node], dim); };

    // How each candidate row sees the motions of this part: an obstacle's row −nᵀu_i, a pair's
    // −nᵀ(u_i − Σ N_j u_j) (the part may hold the node, the face, or both).
    const int part_index = static_cast<int>(p);
    std::vector<Eigen::RowVectorXd> rows;
    for (const Candidate& candidate : model.candidates) {
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(k);
      bool touches = false;
      if (candidate.pair < 0) {
        if (freedom.part[candidate.node] != part_index) continue;
        const Eigen::Vector3d n =
            project(model.scene.obstacles[candidate.obstacle], model.mesh.nodes[candidate.node]).normal;
        for (int j = 0; j < k; ++j) row[j] = -n.dot(motion(j, candidate.node));
        touches = true;
      } else {
        const Eigen::Vector3d& n = candidate.normal;
        if (freedom.part[candidate.node] == part_index) {
          for (int j = 0; j < k; ++j) row[j] -= n.dot(motion(j, candidate.node));
          touches = true;
        }
        for (int f = 0; f < candidate.n_face_nodes; ++f) {
          const int node = candidate.face_nodes[static_cast<size_t>(f)];
          if (freedom.part[node] != part_index) continue;
          for (int j = 0; j < k; ++j) row[j] += candidate.weights[static_cast<size_t>(f)] * n.dot(motion(j, node));
          touches = true;
        }
      }
      if (touches) rows.push_back(row);
      // Friction holds what it can across the row (Q ≤ μP: the solve says whether it does):
      // each tangent sees the motion as t·(u_i − Σ N_j u_j).
      const FrictionSpec* friction = friction_of(model, candidate);
      if (!touches || !friction || !(friction->coefficient > 0 || friction->threshold > 0)) continue;
      for (const Eigen::Vector3d& t : row_tangents(model, candidate)) {
        Eigen::RowVectorXd along = Eigen::RowVectorXd::Zero(k);
        if (freedom.part[candidate.node] == part_index)
          for (int j = 0; j < k; ++j) along[j] += t.dot(motion(j, candidate.node));
        for (int f = 0; f < candidate.n_face_nodes; ++f) {
          const int node = candidate.face_nodes[static_cast<size_t>(f)];
          if (freedom.part[node] == part_index)
            for (int j = 0; j < k; ++j) along[j] -= candidate.weights[static_cast<size_t>(f)] * t.dot(motion(j, node));
        }
        rows.push_back(along);
      }
    }
    Eigen::MatrixXd G(static_cast<long>(rows.size()), k);
    for (size_t r = 0; r < rows.size(); ++r) G.row(static_cast<long>(r)) = rows[r];

    Eigen::VectorXd F = Eigen::VectorXd::Zero(k);
    double total = 0;  // Σ |f_i|: the size the drive is measured against
    for (int node = 0; node < n_nodes; ++node) {
      if (freedom.part[node] != static_cast<int>(p)) continue;
      Eigen::Vector3d f = Eigen::Vector3d::Zero();
      f.head(dim) = force.segment(dim * node, dim);
      total += f.norm();
      for (int j = 0; j < k; ++j) F[j] += f.dot(motion(j, node));
    }
    add_turning_work(model, freedom, part_index, F, total);
    const Eigen::MatrixXd unseen = unseen_combinations(G, k);
    if (unseen.cols() > 0 && total > 0) {
      const Eigen::VectorXd drive = unseen.transpose() * F;
      if (drive.norm() > 1e-9 * total)
        refuse_free_part(model, freedom, static_cast<int>(p), part.null * unseen, kNothingHolds);
    }

    for (int j = 0; j < k; ++j) {
      FreeMotion free;
      free.rigid = part.null.col(j);
      free.centre = part.centre;
      free.extent = part.extent;
      free.part = static_cast<int>(p);
      free.first_node = part.first_node;
      model.free_motions.push_back(free);
      Eigen::VectorXd column = Eigen::VectorXd::Zero(dim * n_nodes);
      for (int node = 0; node < n_nodes; ++node)
        if (freedom.part[node] == static_cast<int>(p)) column.segment(dim * node, dim) = motion(j, node).head(dim);
      columns.push_back(column);
    }
  }
  Eigen::MatrixXd at_nodes(dim * n_nodes, static_cast<long>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j) at_nodes.col(static_cast<long>(j)) = columns[j];
  return at_nodes;
}

Eigen::MatrixXd free_modes_on_dofs(const Model& model, const Eigen::MatrixXd& at_nodes) {
  const int dim = model.dim;
  const Eigen::MatrixXd Q = model.rotation.topLeftCorner(dim, dim);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(model.n_free, at_nodes.cols());
  Eigen::MatrixXd at_dofs(model.rigid_rotations.empty() ? 0 : at_nodes.rows(), at_nodes.cols());
  for (int node = 0; node < model.mesh.n_nodes(); ++node) {
    const Eigen::MatrixXd frame = dof_frame(model, node);
    for (long j = 0; j < at_nodes.cols(); ++j) {
      const Eigen::VectorXd global = Q * at_nodes.block(dim * node, j, dim, 1);
      for (int c = 0; c < dim; ++c) {
        const int column = model.free_index[dim * node + c];
        if (column >= 0) R(column, j) = frame.col(c).dot(global);
        if (at_dofs.rows() > 0) at_dofs(dim * node + c, j) = frame.col(c).dot(global);
      }
    }
  }
  if (at_dofs.rows() > 0) fit_turning_surfaces(model, at_dofs, R);  // a turning surface's translations and angles
  return R;
}

}  // namespace contactqp::detail

namespace contactqp {

std::string describe_free_motion(const Model& model, const Eigen::VectorXd& d, const std::string& verb) {
  const Eigen::MatrixXd& R = model.free_modes;
  if (R.cols() == 0 || d.size() != R.rows()) return "";
  // d = R c: the coefficients of the free motions, then the motion of each part they move.
  const Eigen::VectorXd c = R.colPivHouseholderQr().solve(d);
  std::string text;
  std::vector<char> done(model.free_motions.size(), 0);
  for (size_t j = 0; j < model.free_motions.size(); ++j) {
    if (done[j]) continue;
    const FreeMotion& first = model.free_motions[j];
    Eigen::VectorXd rigid = Eigen::VectorXd::Zero(first.rigid.size());
    for (size_t i = j; i < model.free_motions.size(); ++i)
      if (model.free_motions[i].part == first.part) {
        rigid += c[static_cast<long>(i)] * model.free_motions[i].rigid;
        done[i] = 1;
      }
    if (rigid.norm() <= 1e-9 * c.norm()) continue;
    detail::PartFreedom part;
    part.centre = first.centre;
    part.extent = first.extent;
    // With a verb the subject too: "the body", or the body's name in a scene with several.
    const std::string subject =
        verb.empty()           ? ""
        : model.bodies.empty() ? "the body " + verb + " "
                               : "body `" + model.bodies[model.body_of_node(first.first_node)].name + "` " + verb + " ";
    text += (text.empty() ? "" : ", ") + subject + detail::describe_motion(model, part, rigid);
  }
  return text;
}

}  // namespace contactqp
