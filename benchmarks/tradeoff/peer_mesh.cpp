#include "peer_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contactqp/model.hpp"

namespace contactqp::bench {
namespace {

// max over a ∈ A of min over b ∈ B of |a − b|, searching B sorted by x within `window` of a.x.
double max_nearest_distance(const std::vector<Eigen::Vector3d>& A, std::vector<Eigen::Vector3d> B, double window) {
  std::sort(B.begin(), B.end(), [](const Eigen::Vector3d& p, const Eigen::Vector3d& q) { return p.x() < q.x(); });
  double worst = 0;
  for (const Eigen::Vector3d& a : A) {
    auto it = std::lower_bound(B.begin(), B.end(), a.x() - window,
                               [](const Eigen::Vector3d& p, double x) { return p.x() < x; });
    double nearest = std::numeric_limits<double>::infinity();
    for (; it != B.end() && it->x() <= a.x() + window; ++it) nearest = std::min(nearest, (*it - a).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

}  // namespace

PeerMeshCheck check_peer_mesh(const nlohmann::json& scene, const std::string& msh, const Mesh& mesh) {
  nlohmann::json from_file = scene;
  from_file["body"] = {{"shape", "mesh"}, {"file", msh}, {"symmetry", scene["body"].value("symmetry", false)}};
  from_file["contact"] = {{"boundary", "arc"}};
  from_file.erase("solver");
  Model model = build_model(parse_scene(from_file.dump(), msh));
  const QuadraticProgram qp = assemble_qp(model);

  PeerMeshCheck check;
  check.file = msh;
  check.nodes = model.mesh.n_nodes();
  check.triangles = model.mesh.n_elements();
  check.dofs = qp.n_dofs();
  check.constraints = qp.n_constraints();
  double extent = 0;
  for (const Eigen::Vector3d& node : mesh.nodes) extent = std::max(extent, node.cwiseAbs().maxCoeff());
  check.max_node_distance = max_nearest_distance(mesh.nodes, model.mesh.nodes, 1e-9 * std::max(extent, 1e-300));
  if (check.nodes != mesh.n_nodes()) check.max_node_distance = std::numeric_limits<double>::infinity();
  return check;
}

}  // namespace contactqp::bench
