// The curvature of a boundary where it touches, fitted through the nodes that carry force: for a
// mesh body, whose shape the scene does not state, Hertz's comparison needs it (hertz.cpp for an
// obstacle, pair_contact.cpp for a pair).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

namespace contactqp {

// Signed curvature of the circle (2D) or sphere (3D) A|x|² + D·x + F = 0 through `points`,
// fitted in centred, scaled coordinates (exact for points on a circle or sphere, 0 for points on
// a line or plane); positive when the boundary is convex towards `towards` (a direction from the
// body to what it touches). nullopt with fewer than four points (2D) or six (3D), or a
// degenerate fit.
std::optional<double> fitted_curvature(const std::vector<Eigen::Vector3d>& points, int dim,
                                       const Eigen::Vector3d& towards);

}  // namespace contactqp
