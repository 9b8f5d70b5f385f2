#include "half_disc_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>

#include "gmsh_model.hpp"
#include "graded_size.hpp"
#include "qp/pi.hpp"
#include "refine.hpp"

namespace contactqp::detail {
namespace {

GradedSize unit_sizes(const HalfDiscMeshRequest& request) {
  return {request.size / request.radius, request.contact_size / request.radius, request.grading};
}

}  // namespace

double estimate_half_disc_triangles(const HalfDiscMeshRequest& request) {
  // In units of R: the fine arc's length is its angle.
  const double area = request.symmetry ? kPi / 4 : kPi / 2;
  return estimate_graded_triangles(unit_sizes(request), area, total_length(request.fine));
}

SnapToBoundary half_disc_snap() {
  // Refined in units of R, where the arc is the unit circle about (0, 1), then scaled.
  return [](const std::string& boundary, const Eigen::Vector3d& x) -> Eigen::Vector3d {
    if (boundary != "arc") return x;
    const Eigen::Vector3d centre(0.0, 1.0, 0.0);
    return centre + (x - centre).normalized();
  };
}

CoarseMesh coarse_half_disc(const HalfDiscMeshRequest& request) {
  GmshSession session;
  // Mesh the unit geometry and scale afterwards: the mesh of a scaled scene is then exactly
  // the scaled mesh (Gmsh's geometric tolerances are absolute).
  const double phi_start = request.symmetry ? 0.0 : -kPi / 2, phi_end = kPi / 2;

  gmsh::model::add("half_disc");
  namespace geo = gmsh::model::geo;
  auto arc_point = [](double phi) { return geo::addPoint(std::sin(phi), 1.0 - std::cos(phi), 0.0); };

  // Breakpoints of the arc: its ends, the ends of the fine arcs, and φ = 0 (Gmsh's circle
  // arcs must span less than π).
  const std::vector<double> breaks = breakpoints(phi_start, phi_end, request.fine,
                                                 request.symmetry ? std::vector<double>{} : std::vector<double>{0.0});

  const int centre = geo::addPoint(0.0, 1.0, 0.0);
  std::vector<int> points;
  for (double phi : breaks) points.push_back(arc_point(phi));
  std::vector<int> arcs, fine_arcs, loop;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const int arc = geo::addCircleArc(points[k], centre, points[k + 1]);
    arcs.push_back(arc);
    loop.push_back(arc);
    const double middle = 0.5 * (breaks[k] + breaks[k + 1]);
    if (inside(request.fine, middle)) fine_arcs.push_back(arc);
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
  if (symmetry_line >= 0)
    gmsh::model::setPhysicalName(1, gmsh::model::addPhysicalGroup(1, {symmetry_line}), "symmetry");
  gmsh::model::addPhysicalGroup(2, {surface});

  const double first = request.fine.empty() ? phi_start : request.fine.front().first;
  const int closest = std::lower_bound(breaks.begin(), breaks.end(), first - 1e-9) - breaks.begin();
  GradedSize sizes = unit_sizes(request);
  const double coarsening = std::ldexp(1.0, request.refinements);
  sizes.size *= coarsening;
  sizes.contact_size *= coarsening;
  sizes.grading *= coarsening;
  if (request.size_field)
    set_size_field(request.size_field, request.radius);
  else
    set_graded_size_field(sizes, fine_arcs, total_length(request.fine),
                          points[std::min<size_t>(closest, points.size() - 1)]);
  gmsh::option::setNumber("Mesh.ElementOrder", request.refinements > 0 ? 1 : request.order);
  gmsh::model::mesh::generate(2);
  throw_if_gmsh_failed();
  return coarse_from_gmsh(request.refinements, request.order, request.radius, half_disc_snap());
}

Mesh mesh_half_disc(const HalfDiscMeshRequest& request) {
  const CoarseMesh coarse = coarse_half_disc(request);
  return refine_coarse(coarse, coarse.mesh);
}

}  // namespace contactqp::detail
