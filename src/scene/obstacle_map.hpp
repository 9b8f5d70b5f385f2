// An obstacle carried by a rigid map of space: the scene's rotation (transform.cpp) and a body's
// placement into its own frame (model/bodies_model.cpp) move obstacles through this one visitor,
// which names every kind of obstacle: a new kind fails to compile here until it says what it
// holds (points, directions, a side), instead of falling into a branch that assumes a centre.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "contactqp/scene.hpp"

namespace contactqp::detail {

struct RigidMap {
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> point;      // a point's image
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> direction;  // a direction's image (normals, axes)
  bool reflection = false;  // reverses orientation: the side a profile keeps its body on swaps
};

ObstacleSpec mapped(const ObstacleSpec& obstacle, const RigidMap& map);

}  // namespace contactqp::detail
