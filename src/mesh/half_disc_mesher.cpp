#include "half_disc_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>

#include "gmsh_model.hpp"
#include "graded_size.hpp"

namespace contactqp::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;

GradedSize unit_sizes(const HalfDiscMeshRequest& request) {
  return {request.size / request.radius, request.contact_size / request.radius, request.grading};
}

}  // namespace

double estimate_half_disc_triangles(const HalfDiscMeshRequest& request) {
  // In units of R: the fine arc's length is its angle.
  const double area = request.symmetry ? kPi / 4 : kPi / 2;
  return estimate_graded_triangles(unit_sizes(request), area, std::max(0.0, request.fine_to - request.fine_from));
}

Mesh mesh_half_disc(const HalfDiscMeshRequest& request) {
  GmshSession session;
  // Mesh the unit geometry and scale afterwards: the mesh of a scaled scene is then exactly
  // the scaled mesh (Gmsh's geometric tolerances are absolute).
  const double phi_start = request.symmetry ? 0.0 : -kPi / 2, phi_end = kPi / 2;
  const double fine_from = std::clamp(request.fine_from, phi_start, phi_end);
  const double fine_to = std::clamp(request.fine_to, phi_start, phi_end);

  gmsh::model::add("half_disc");
  namespace geo = gmsh::model::geo;
  auto arc_point = [](double phi) { return geo::addPoint(std::sin(phi), 1.0 - std::cos(phi), 0.0); };

  // Breakpoints of the arc: its ends, the ends of the fine arc, and φ = 0 (Gmsh's circle
  // arcs must span less than π).
  std::vector<double> breaks = {phi_start, phi_end, fine_from, fine_to};
  if (!request.symmetry) breaks.push_back(0.0);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }),
               breaks.end());

  const int centre = geo::addPoint(0.0, 1.0, 0.0);
  std::vector<int> points;
  for (double phi : breaks) points.push_back(arc_point(phi));
  std::vector<int> arcs, fine_arcs, loop;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const int arc = geo::addCircleArc(points[k], centre, points[k + 1]);
    arcs.push_back(arc);
    loop.push_back(arc);
    const double middle = 0.5 * (breaks[k] + breaks[k + 1]);
    if (middle > fine_from && middle < fine_to) fine_arcs.push_back(arc);
  }
  int top, symmetry_line = -1;
  if (request.symmetry) {
    top = geo::addLine(points.back(), centre);
    symmetry_line = geo::addLine(centre, points.front());
    loop.push_back(top);
    loop.push_back(symmetry_line);
  } else {
    top = geo::addLine(points.back(), points.front());
    loop.push_back(top);
  }
  const int surface = geo::addPlaneSurface({geo::addCurveLoop(loop)});
  geo::synchronize();
  gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, arcs), "arc");
  gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {top}), "top");
  if (symmetry_line >= 0) gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {symmetry_line}), "symmetry");
  gmsh::model::addPhysicalGroup(2, {surface});

  const int closest = std::lower_bound(breaks.begin(), breaks.end(), fine_from - 1e-9) - breaks.begin();
  set_graded_size_field(unit_sizes(request), fine_arcs, fine_to - fine_from,
                        points[std::min<size_t>(closest, points.size() - 1)]);
  gmsh::option::setNumber("Mesh.ElementOrder", request.order);
  gmsh::model::mesh::generate(2);
  Mesh mesh = mesh_from_gmsh(request.radius);
  mesh.regions.clear();  // the generated body has no named regions
  return mesh;
}

}  // namespace contactqp::detail
