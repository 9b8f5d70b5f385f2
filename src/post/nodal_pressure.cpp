// Nodal contact pressure: force over tributary, with the vertices of 6-node faces (whose
// consistent weight is 0) given the mean pressure of their mid-side neighbours.
#include <map>

#include "contactqp/post.hpp"

namespace contactqp {

std::vector<double> nodal_pressures(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda) {
  const int m = qp.n_constraints();
  const double thickness = model.dim == 2 ? model.scene.body.thickness : 1.0;
  std::vector<double> pressure(m, 0.0);
  std::map<std::pair<int, int>, int> row_of;  // (node, obstacle) -> row
  bool any_vertex = false;
  for (int i = 0; i < m; ++i) {
    const Candidate& c = model.candidates[i];
    row_of[{c.node, c.obstacle}] = i;
    if (c.tributary > 0)
      pressure[i] = lambda[i] / (c.tributary * thickness);
    else
      any_vertex = true;
  }
  if (!any_vertex || model.dim != 3 || model.mesh.order != 2) return pressure;
  // Each vertex of a 6-node face (v0 v1 v2 m01 m12 m20) neighbours the two mid-sides beside it.
  static const int kBeside[3][2] = {{3, 5}, {3, 4}, {4, 5}};
  std::vector<double> sum(m, 0.0);
  std::vector<int> count(m, 0);
  auto faces = model.mesh.boundaries.find(model.scene.contact.boundary);
  if (faces == model.mesh.boundaries.end() && model.pair_sides.empty()) return pressure;
  for (const BoundaryFace& face : faces == model.mesh.boundaries.end() ? std::vector<BoundaryFace>{} : faces->second) {
    for (int k = 0; k < 3; ++k) {
      for (int o = 0; o < static_cast<int>(model.scene.obstacles.size()); ++o) {
        auto vertex = row_of.find({face.nodes[k], o});
        if (vertex == row_of.end() || model.candidates[vertex->second].tributary > 0) continue;
        for (int side : kBeside[k]) {
          auto mid = row_of.find({face.nodes[side], o});
          if (mid == row_of.end()) continue;
          sum[vertex->second] += pressure[mid->second];
          ++count[vertex->second];
        }
      }
    }
  }
  // Rows between bodies: the same on each pair's node side (keyed by pair, not obstacle).
  std::map<std::pair<int, int>, int> pair_row_of;  // (node, pair) -> row
  for (int i = 0; i < m; ++i)
    if (model.candidates[i].pair >= 0) pair_row_of[{model.candidates[i].node, model.candidates[i].pair}] = i;
  for (size_t p = 0; p < model.pair_sides.size() && !pair_row_of.empty(); ++p) {
    const ContactPair& pair = model.scene.pairs[p];
    const int n = model.pair_sides[p].node_side;
    auto pair_faces = model.mesh.boundaries.find(model.bodies[pair.body[n]].name + "." + pair.boundary[n]);
    if (pair_faces == model.mesh.boundaries.end()) continue;
    for (const BoundaryFace& face : pair_faces->second)
      for (int k = 0; k < 3; ++k) {
        auto vertex = pair_row_of.find({face.nodes[k], static_cast<int>(p)});
        if (vertex == pair_row_of.end() || model.candidates[vertex->second].tributary > 0) continue;
        for (int side : kBeside[k]) {
          auto mid = pair_row_of.find({face.nodes[side], static_cast<int>(p)});
          if (mid == pair_row_of.end()) continue;
          sum[vertex->second] += pressure[mid->second];
          ++count[vertex->second];
        }
      }
  }
  for (int i = 0; i < m; ++i)
    if (model.candidates[i].tributary <= 0 && count[i] > 0) pressure[i] = sum[i] / count[i];
  return pressure;
}

}  // namespace contactqp
