// How far two meshes' contact pressures lie apart: the discretisation error of the coarser one
// when the other is much finer (docs/tradeoff.md).
#pragma once

#include <vector>

#include "contactqp/post.hpp"

namespace contactqp::bench {

// ‖p_a − p_b‖_L2 / ‖p_b‖_L2 along the obstacle, for two nodal pressure profiles (each sorted by
// s, linear between its nodes, zero beyond its first and last node). Exact: between the union
// of the nodes both are linear, and 2-point Gauss integrates the squared difference exactly.
// 0 when p_b vanishes.
double relative_l2_difference(const std::vector<ContactProfilePoint>& a, const std::vector<ContactProfilePoint>& b);

}  // namespace contactqp::bench
