#include "rectangle_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>

#include "gmsh_model.hpp"
#include "graded_size.hpp"

namespace contactqp::detail {
namespace {

// The geometry is meshed in units of the height and scaled afterwards (as the half disc is
// in units of R), so a scaled scene has exactly the scaled mesh.
GradedSize unit_sizes(const RectangleMeshRequest& request) {
  return {request.size / request.height, request.contact_size / request.height, request.grading};
}

double fine_length(const RectangleMeshRequest& request) {
  for (const RectangleSide& side : rectangle_sides(request.width, request.height, request.symmetry))
    if (side.name == request.fine_side) return total_length(request.fine) * (side.b - side.a).norm();
  return 0.0;
}

}  // namespace

std::vector<RectangleSide> rectangle_sides(double width, double height, bool symmetry) {
  const double left = symmetry ? 0.0 : -0.5 * width, right = 0.5 * width;
  const Eigen::Vector2d p0(left, 0), p1(right, 0), p2(right, height), p3(left, height);
  return {{"bottom", p0, p1}, {"right", p1, p2}, {"top", p2, p3}, {symmetry ? "symmetry" : "left", p3, p0}};
}

double estimate_rectangle_triangles(const RectangleMeshRequest& request) {
  const double area = (request.symmetry ? 0.5 : 1.0) * request.width * request.height;
  const double h = request.height;
  return estimate_graded_triangles(unit_sizes(request), area / (h * h), fine_length(request) / h);
}

Mesh mesh_rectangle(const RectangleMeshRequest& request) {
  GmshSession session;
  gmsh::model::add("rectangle");
  namespace geo = gmsh::model::geo;
  const double unit = request.height;
  const auto sides = rectangle_sides(request.width / unit, 1.0, request.symmetry);

  // Each side is split at the ends of its fine part; the pieces keep the side's name.
  std::vector<int> corner;
  for (const RectangleSide& side : sides) corner.push_back(geo::addPoint(side.a.x(), side.a.y(), 0.0));
  std::vector<int> loop, fine_curves;
  std::vector<std::vector<int>> curves_of_side(sides.size());
  int fallback_point = corner[0];
  for (size_t s = 0; s < sides.size(); ++s) {
    const RectangleSide& side = sides[s];
    const bool fine = side.name == request.fine_side;
    const std::vector<double> breaks = breakpoints(0.0, 1.0, fine ? request.fine : Intervals{});
    std::vector<int> points = {corner[s]};
    for (size_t k = 1; k + 1 < breaks.size(); ++k) {
      const Eigen::Vector2d x = side.a + breaks[k] * (side.b - side.a);
      points.push_back(geo::addPoint(x.x(), x.y(), 0.0));
    }
    points.push_back(corner[(s + 1) % sides.size()]);
    for (size_t k = 0; k + 1 < points.size(); ++k) {
      const int line = geo::addLine(points[k], points[k + 1]);
      loop.push_back(line);
      curves_of_side[s].push_back(line);
      const double middle = 0.5 * (breaks[k] + breaks[k + 1]);
      if (fine && inside(request.fine, middle)) fine_curves.push_back(line);
      if (fine && !request.fine.empty() && std::abs(breaks[k] - request.fine.front().first) < 1e-9)
        fallback_point = points[k];
    }
  }
  const int surface = geo::addPlaneSurface({geo::addCurveLoop(loop)});
  geo::synchronize();
  for (size_t s = 0; s < sides.size(); ++s)
    gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, curves_of_side[s]), sides[s].name);
  gmsh::model::addPhysicalGroup(2, {surface});

  if (request.size_field)
    set_size_field(request.size_field, unit);
  else
    set_graded_size_field(unit_sizes(request), fine_curves, fine_length(request) / unit, fallback_point);
  gmsh::option::setNumber("Mesh.ElementOrder", request.order);
  gmsh::model::mesh::generate(2);
  throw_if_gmsh_failed();
  Mesh mesh = mesh_from_gmsh(unit);
  mesh.regions.clear();
  return mesh;
}

}  // namespace contactqp::detail
