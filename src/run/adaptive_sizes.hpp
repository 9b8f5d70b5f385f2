// The next mesh of an adaptive run (docs/adaptive.md): from the last mesh's error indicators,
// the element size wanted at each point of each generated body.
#pragma once

#include <functional>
#include <vector>

#include "contactqp/model.hpp"

namespace contactqp::detail {

struct NextMeshLimits {
  double max_growth = 4;         // the next mesh has at most this many times the elements
  std::vector<double> max_size;  // per body: no element larger (its mesh's `size`); 0: the body keeps its mesh
};

struct NextMesh {
  // Per body (Model::bodies, or the one body of a one-body scene): the size wanted at each point
  // of its own frame; empty for a body that keeps its mesh (max_size 0).
  std::vector<std::function<double(const Eigen::Vector3d&)>> size_fields;
  double elements = 0;  // expected elements of the next mesh, every body's
  double estimate = 0;  // η expected on it
};

// Sizes that equidistribute the error: each element's η_T² is taken to scale like h^(2p + d)
// (p the order, d the dimension), so that an element of size h split to size r·h leaves
// η_T² r^(2p) spread over r^(−d) elements; one r per element, each element's share of the
// error the same number e, and e the largest that brings the expected η down to
// `wanted_estimate` within `limits.max_growth` (else the one that reaches that growth). r is
// kept within [1/4, 2] per cycle. A vertex's size is the geometric mean of its elements'.
NextMesh plan_next_mesh(const Model& model, const Eigen::VectorXd& indicator, double wanted_estimate,
                        const NextMeshLimits& limits);

}  // namespace contactqp::detail
