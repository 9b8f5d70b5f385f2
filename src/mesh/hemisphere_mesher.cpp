#include "hemisphere_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gmsh_model.hpp"
#include "qp/pi.hpp"
#include "refine.hpp"

namespace contactqp::detail {
namespace {

// Meshed in units of R and scaled afterwards (as the half disc is): the mesh of a scaled
// scene is then exactly the scaled mesh (Gmsh's geometric tolerances are absolute; lengths
// are rounded in units of R, see unit_length).
GradedSize unit_sizes(const HemisphereMeshRequest& request) {
  return {unit_length(request.size, request.radius), unit_length(request.contact_size, request.radius),
          request.grading};
}

double unit_fine_radius(const HemisphereMeshRequest& request) {
  return unit_length(request.fine_radius, request.radius);
}

// The area of the sphere |x| = ρ about the lowest point that lies in the half ball of radius 1
// centred at (0, 0, 1): points of polar angle θ (from +z) with ρ²/2 ≤ z = ρ cos θ ≤ 1, so
// 2π ρ² (min(1, 1/ρ) − ρ/2) for ρ ≤ √2, nothing beyond. Its integral from 0 is the volume
// within ρ of the lowest point: π ρ³ (8 − 3ρ) / 12 for ρ ≤ 1.
double shell_area(double rho) {
  if (rho <= 0 || rho >= std::sqrt(2.0)) return 0.0;
  return 2 * kPi * rho * rho * std::max(0.0, std::min(1.0, 1 / rho) - rho / 2);
}

double volume_within(double rho) {
  // ∫ shell_area: the closed form up to ρ = 1, then the half ball minus what lies beyond.
  if (rho <= 1) return kPi * rho * rho * rho * (8 - 3 * rho) / 12;
  const double r = std::min(rho, std::sqrt(2.0));
  // For 1 < ρ ≤ √2: ∫_1^ρ 2π (s − s³/2) ds = π (ρ² − 1) − π (ρ⁴ − 1) / 4.
  return 5 * kPi / 12 + kPi * (r * r - 1) - kPi * (r * r * r * r - 1) / 4;
}

}  // namespace

double estimate_hemisphere_elements(const HemisphereMeshRequest& request) {
  const double quarter = request.symmetry ? (request.symmetry_x && request.symmetry_y ? 0.25 : 0.5) : 1.0;
  const double fine = std::min(unit_fine_radius(request), std::sqrt(2.0));
  return estimate_graded_tetrahedra(unit_sizes(request), quarter * 2 * kPi / 3, quarter * volume_within(fine),
                                    [quarter, fine](double d) { return quarter * shell_area(fine + d); });
}

SnapToBoundary hemisphere_snap() {
  // Refined in units of R, where the sphere is the unit one about (0, 0, 1), then scaled.
  // Projecting about the centre keeps a node of the top (z = 1) or of a symmetry plane
  // (x = 0, y = 0) on it: the centre lies on all three, so a rim node stays on both faces.
  return [](const std::string& boundary, const Eigen::Vector3d& x) -> Eigen::Vector3d {
    if (boundary != "surface") return x;
    const Eigen::Vector3d centre(0.0, 0.0, 1.0);
    return centre + (x - centre).normalized();
  };
}

CoarseMesh coarse_hemisphere(const HemisphereMeshRequest& request) {
  GmshSession session;
  gmsh::model::add("hemisphere");
  namespace occ = gmsh::model::occ;
  // The half ball is the ball cut by the slab (or the quarter slab) z ∈ [0, 1]: OpenCASCADE
  // gives it a spherical face, a flat top and, for the quarter, two planar faces.
  const int ball = occ::addSphere(0, 0, 1, 1);
  const bool cut_x = request.symmetry && request.symmetry_x, cut_y = request.symmetry && request.symmetry_y;
  const int slab = occ::addBox(cut_x ? 0 : -1.5, cut_y ? 0 : -1.5, 0, cut_x ? 1.5 : 3, cut_y ? 1.5 : 3, 1);
  gmsh::vectorpair body;
  std::vector<gmsh::vectorpair> map;
  occ::intersect({{3, ball}}, {{3, slab}}, body, map);
  occ::synchronize();
  throw_if_gmsh_failed();

  // The faces are told apart by their bounding boxes (OpenCASCADE numbers them as it likes).
  std::vector<int> surface, top, symmetry_x, symmetry_y;
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  const double tolerance = 1e-6;
  for (const auto& [dim, tag] : faces) {
    double x0, y0, z0, x1, y1, z1;
    gmsh::model::getBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1);
    if (z0 > 1 - tolerance)
      top.push_back(tag);
    else if (cut_x && x1 < tolerance)
      symmetry_x.push_back(tag);
    else if (cut_y && y1 < tolerance)
      symmetry_y.push_back(tag);
    else
      surface.push_back(tag);
  }
  auto name = [](int dim, const std::vector<int>& tags, const char* text) {
    gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, tags), text);
  };
  name(2, surface, "surface");
  name(2, top, "top");
  if (cut_x) name(2, symmetry_x, "symmetry_x");
  if (cut_y) name(2, symmetry_y, "symmetry_y");
  std::vector<int> volumes;
  for (const auto& [dim, tag] : body) volumes.push_back(tag);
  gmsh::model::addPhysicalGroup(3, volumes);

  char distance[128];
  std::snprintf(distance, sizeof distance, "Max(0, Sqrt(x*x + y*y + z*z) - (%.17g))", unit_fine_radius(request));
  // With refinements, Gmsh meshes sizes and grading 2ⁿ times larger (as the half disc): split
  // n times, the coarse size function of the distance is the requested one again.
  GradedSize sizes = unit_sizes(request);
  const double coarsening = std::ldexp(1.0, request.refinements);
  sizes.size *= coarsening;
  sizes.contact_size *= coarsening;
  sizes.grading *= coarsening;
  if (request.size_field)
    set_size_field(request.size_field, request.radius, request.volume_algorithm);
  else
    set_graded_size_expression(sizes, distance, request.volume_algorithm);
  gmsh::option::setNumber("Mesh.ElementOrder", request.refinements > 0 ? 1 : request.order);
  gmsh::model::mesh::generate(3);
  throw_if_gmsh_failed();
  return coarse_from_gmsh(request.refinements, request.order, request.radius, hemisphere_snap());
}

Mesh mesh_hemisphere(const HemisphereMeshRequest& request) {
  const CoarseMesh coarse = coarse_hemisphere(request);
  return refine_coarse(coarse, coarse.mesh);
}

}  // namespace contactqp::detail
