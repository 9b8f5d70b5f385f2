// What a symmetric model's part stands for: its mirror images about each symmetry plane
// (body.symmetry; the planes are the scene's own x = 0 and y = 0, turned by its transform).
#include "contactqp/post.hpp"

namespace contactqp {

double mirror_copies(const Model& model) { return symmetry_copies(model.scene.body, model.dim); }

Eigen::Vector3d mirror_mean(const Model& model, const Eigen::Vector3d& point) {
  const std::vector<std::string> planes = symmetry_boundaries(model.scene.body, model.dim);
  // Every plane of the shape: what is left is the component along their common line (the 2D
  // y axis, the 3D z axis), taken so, as it always was.
  if (static_cast<int>(planes.size()) == model.dim - 1) {
    const Eigen::Vector3d axis = model.rotation.col(model.dim - 1);
    return point.dot(axis) * axis;
  }
  Eigen::Vector3d mean = point;
  for (const std::string& plane : planes) {
    const Eigen::Vector3d across = model.rotation.col(symmetry_component(plane));
    mean -= mean.dot(across) * across;
  }
  return mean;
}

Eigen::Vector3d whole_body_sum(const Model& model, const Eigen::Vector3d& vector) {
  return mirror_copies(model) * mirror_mean(model, vector);
}

}  // namespace contactqp
