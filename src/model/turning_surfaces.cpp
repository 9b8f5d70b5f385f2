// The rigid surfaces of force loads with a moment (RigidForceLoad::moment): their angles as
// columns of K with each tied DOF's lever arm, and the values of those columns for a given
// displacement of the nodes.
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <map>

#include "contactqp/errors.hpp"
#include "fe/loads.hpp"
#include "model_parts.hpp"

namespace contactqp::detail {

void turn_rigid_surfaces(Model& model, const Scene& scene, const Eigen::Matrix3d& rotation,
                         const NodesOfBoundary& nodes_of) {
  const int dim = model.dim;
  model.rigid_rotations.clear();
  model.levers.clear();
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const RigidForceLoad* load = scene.loads[l].as<RigidForceLoad>();
    if (!load || !load->turns()) continue;
    std::vector<int> nodes = nodes_of(load->boundary);
    std::sort(nodes.begin(), nodes.end());
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    if (load->about) {
      centre = rotation * *load->about;
    } else if (model.mesh.boundaries.count(load->boundary)) {
      centre = boundary_centroid(model.mesh, load->boundary);
    } else {  // a part of a distributed mesh: the mean of its nodes
      for (int node : nodes) centre += model.mesh.nodes[node] / static_cast<double>(nodes.size());
    }
    double size = 0;
    for (int node : nodes) size = std::max(size, (model.mesh.nodes[node] - centre).norm());
    for (int k = 0; k < 3; ++k)  // a centroid on an axis of the mesh is on it, not round-off away
      if (std::abs(centre[k]) <= 1e-12 * size) centre[k] = 0;
    for (int a = 0; a < 3; ++a) {
      if (!load->moment[a]) continue;
      RigidRotation turn;
      turn.load = static_cast<int>(l);
      turn.axis = a;
      turn.column = model.n_free++;
      turn.moment = *load->moment[a];
      turn.centre = centre;
      turn.nodes = nodes;
      const Eigen::Vector3d axis = rotation.col(a);
      // The turn must move the tied DOFs of some component unequally: an equal share along
      // each is a translation, which the surface has already.
      Eigen::Vector3d lowest = Eigen::Vector3d::Constant(HUGE_VAL), highest = -lowest;
      for (int node : nodes) {
        const Eigen::Vector3d moved = axis.cross(model.mesh.nodes[node] - centre);
        const Eigen::MatrixXd frame = dof_frame(model, node);
        for (int c = 0; c < dim; ++c) {
          if (!load->value[c]) continue;  // a free component takes the turn in its own DOF
          Eigen::Vector3d along = Eigen::Vector3d::Zero();
          along.head(dim) = frame.col(c);
          const double weight = along.dot(moved);
          lowest[c] = std::min(lowest[c], weight);
          highest[c] = std::max(highest[c], weight);
          if (weight != 0.0) model.levers.push_back({dim * node + c, turn.column, weight});
        }
      }
      double spread = 0;
      for (int c = 0; c < dim; ++c)
        if (load->value[c]) spread = std::max(spread, highest[c] - lowest[c]);
      if (!(spread > 1e-9 * size)) {
        const std::string field = scene.loads[l].path + ".moment" + (dim == 2 ? "" : "[" + std::to_string(a) + "]");
        throw InputError(field, "= " + format_value(turn.moment) + ": turning \"" + load->boundary + "\" about " +
                                    "xyz"[a] + " moves it along no component the force ties (its lever arm is 0); " +
                                    "give the force along a component the turn moves");
      }
      model.rigid_rotations.push_back(std::move(turn));
    }
  }
  std::sort(model.levers.begin(), model.levers.end(),
            [](const Lever& a, const Lever& b) { return a.dof != b.dof ? a.dof < b.dof : a.column < b.column; });
}

}  // namespace contactqp::detail

namespace contactqp {

void fit_turning_surfaces(const Model& model, const Eigen::MatrixXd& dof_values, Eigen::MatrixXd& columns) {
  std::vector<int> loads;
  for (const RigidRotation& turn : model.rigid_rotations)
    if (std::find(loads.begin(), loads.end(), turn.load) == loads.end()) loads.push_back(turn.load);
  for (int load : loads) {
    // The load's unknowns: its translations' columns and its angles' columns, numbered locally.
    std::map<int, int> unknown;
    std::vector<int> components;
    for (const RigidSurface& surface : model.rigid_surfaces)
      if (surface.load == load) {
        unknown.emplace(surface.column, static_cast<int>(unknown.size()));
        components.push_back(surface.component);
      }
    const std::vector<int>* nodes = nullptr;
    for (const RigidRotation& turn : model.rigid_rotations)
      if (turn.load == load) {
        unknown.emplace(turn.column, static_cast<int>(unknown.size()));
        nodes = &turn.nodes;
      }
    // One equation per tied DOF: its translation plus its levers times the angles.
    const long n_rows = static_cast<long>(nodes->size() * components.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n_rows, static_cast<long>(unknown.size()));
    Eigen::MatrixXd b(n_rows, dof_values.cols());
    long row = 0;
    for (int node : *nodes)
      for (int c : components) {
        const int dof = model.dim * node + c;
        for_each_column(model, dof, [&](int column, double w) { A(row, unknown.at(column)) += w; });
        b.row(row++) = dof_values.row(dof);
      }
    const Eigen::MatrixXd z = A.colPivHouseholderQr().solve(b);
    for (const auto& [column, k] : unknown) columns.row(column) = z.row(k);
  }
}

}  // namespace contactqp
