// How far each body that only its contacts hold moved as a whole (docs/bodies.md): the volume
// mean of u over the body, along the scene's axes that its free motions translate it along.
#include <cmath>

#include "contactqp/post.hpp"

namespace contactqp {
namespace {

// ∫ N_i over an element as a share of its measure: equal at the vertices of linear elements; for
// quadratic ones the vertex functions integrate to 0 (triangle) or −1/20 (tetrahedron) and the
// mid-edge ones to 1/3 and 1/5.
std::vector<double> node_shares(const Mesh& mesh) {
  const int npe = mesh.nodes_per_element(), vertices = mesh.dim + 1;
  if (npe == vertices) return std::vector<double>(npe, 1.0 / npe);
  std::vector<double> share(npe, mesh.dim == 2 ? 1.0 / 3.0 : 1.0 / 5.0);
  for (int i = 0; i < vertices; ++i) share[i] = mesh.dim == 2 ? 0.0 : -1.0 / 20.0;
  return share;
}

}  // namespace

std::vector<FloatingBody> floating_bodies(const Model& model, const Eigen::VectorXd& u) {
  const int dim = model.dim;
  const int n_bodies = model.bodies.empty() ? 1 : static_cast<int>(model.bodies.size());
  // Which axes each body is free to translate along: a free motion's translation part (its rigid
  // coordinates' first dim entries, in the scene's own axes: the motions are found before the
  // model is turned).
  std::vector<Eigen::Vector3d> along(n_bodies, Eigen::Vector3d::Zero());
  for (const FreeMotion& motion : model.free_motions) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    t.head(dim) = motion.rigid.head(dim);
    if (t.norm() <= 1e-9 * motion.rigid.norm()) continue;  // a rotation about the centroid
    along[model.body_of_node(motion.first_node)] += t.cwiseAbs() / t.norm();
  }
  std::vector<Eigen::Vector3d> integral(n_bodies, Eigen::Vector3d::Zero());
  std::vector<double> measure(n_bodies, 0.0);
  if (model.free_motions.empty()) return {};
  const Eigen::VectorXd displacement = full_displacement(model, u);
  const Mesh& mesh = model.mesh;
  const std::vector<double> share = node_shares(mesh);
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int b = body_of_element(model, e);
    if (along[b].norm() == 0) continue;
    const double V = std::abs(element_measure(mesh, e));
    const int* v = mesh.element(e);
    for (size_t i = 0; i < share.size(); ++i)
      integral[b].head(dim) += V * share[i] * displacement.segment(dim * v[i], dim);
    measure[b] += V;
  }
  std::vector<FloatingBody> out;
  for (int b = 0; b < n_bodies; ++b) {
    if (along[b].norm() == 0 || !(measure[b] > 0)) continue;
    FloatingBody entry;
    entry.body = model.bodies.empty() ? "body" : model.bodies[b].name;
    const Eigen::Vector3d mean = model.rotation.transpose() * integral[b] / measure[b];  // the scene's axes
    for (int c = 0; c < dim; ++c)
      if (along[b][c] > 1e-6) entry.translation[c] = mean[c] + 0.0;
    out.push_back(entry);
  }
  return out;
}

}  // namespace contactqp
