#include "box_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "gmsh_model.hpp"
#include "qp/pi.hpp"

namespace contactqp::detail {
namespace {

// The geometry is meshed in units of the height and scaled afterwards (as the rectangle is),
// so a scaled scene has exactly the scaled mesh (lengths rounded: see unit_length).
GradedSize unit_sizes(const BoxMeshRequest& request) {
  return {unit_length(request.size, request.height), unit_length(request.contact_size, request.height),
          request.grading};
}

// The fine disc in units of the height: centre and radius.
Eigen::Vector2d unit_centre(const BoxMeshRequest& request) {
  return {unit_length(request.fine_centre.x(), request.height), unit_length(request.fine_centre.y(), request.height)};
}
double unit_radius(const BoxMeshRequest& request) { return unit_length(request.fine_radius, request.height); }

// The box in units of the height: [x0, x1] × [y0, y1] × [0, 1].
struct UnitBox {
  double x0, x1, y0, y1;
  bool contains(double x, double y, double z) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1 && z <= 1; }
};

UnitBox unit_box(const BoxMeshRequest& request) {
  const double w = unit_length(request.width, request.height), d = unit_length(request.depth, request.height);
  const bool cut_x = request.symmetry && request.symmetry_x, cut_y = request.symmetry && request.symmetry_y;
  return {cut_x ? 0.0 : -w / 2, w / 2, cut_y ? 0.0 : -d / 2, d / 2};
}

// The area of the body's points at distance d > 0 from the fine disc (centre c, radius r):
// the surface at distance d from a disc lying on the half-space z ≥ 0 is a flat disc at
// height d and the quarter torus around its rim, each clipped to the box by a midpoint rule.
double shell_area(const UnitBox& box, const Eigen::Vector2d& c, double r, double d) {
  const int n = 48;
  double area = 0;
  for (int j = 0; j < n; ++j) {
    const double phi = 2 * kPi * (j + 0.5) / n, cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    for (int i = 0; i < n; ++i) {
      const double rho = r * (i + 0.5) / n;  // the flat part, ring by ring
      if (box.contains(c.x() + rho * cos_phi, c.y() + rho * sin_phi, d)) area += rho * (r / n) * (2 * kPi / n);
      const double alpha = 0.5 * kPi * (i + 0.5) / n;  // the rounded part: rim + d (sin α, cos α)
      const double out = r + d * std::sin(alpha);
      if (box.contains(c.x() + out * cos_phi, c.y() + out * sin_phi, d * std::cos(alpha)))
        area += out * d * (0.5 * kPi / n) * (2 * kPi / n);
    }
  }
  return area;
}

}  // namespace

double estimate_box_elements(const BoxMeshRequest& request) {
  const UnitBox box = unit_box(request);
  const Eigen::Vector2d c = unit_centre(request);
  const double r = unit_radius(request);
  return estimate_graded_tetrahedra(unit_sizes(request), (box.x1 - box.x0) * (box.y1 - box.y0), 0.0,
                                    [&](double d) { return shell_area(box, c, r, d); });
}

Mesh mesh_box(const BoxMeshRequest& request) {
  GmshSession session;
  gmsh::model::add("box");
  namespace occ = gmsh::model::occ;
  const UnitBox box = unit_box(request);
  int volume = occ::addBox(box.x0, box.y0, 0, box.x1 - box.x0, box.y1 - box.y0, 1);
  const double rim = unit_length(request.rim_radius, request.height);
  if (rim > 0) {
    // The rim's disc, cut to the bottom face, splits that face: the volume is fragmented by it.
    const Eigen::Vector2d c = unit_centre(request);
    const int disc = occ::addDisk(c.x(), c.y(), 0, rim, rim);
    const int bottom = occ::addRectangle(box.x0, box.y0, 0, box.x1 - box.x0, box.y1 - box.y0);
    gmsh::vectorpair on_bottom, fragments;
    std::vector<gmsh::vectorpair> map;
    occ::intersect({{2, disc}}, {{2, bottom}}, on_bottom, map);
    occ::fragment({{3, volume}}, on_bottom, fragments, map);
    for (const auto& [dim, tag] : fragments)
      if (dim == 3) volume = tag;
  }
  occ::synchronize();
  throw_if_gmsh_failed();

  // The faces are told apart by their bounding boxes (OpenCASCADE numbers them as it likes).
  struct Side {
    const char* name;
    int axis;  // 0 x, 1 y, 2 z
    double at;
  };
  const Side sides[] = {{"bottom", 2, 0.0},
                        {"top", 2, 1.0},
                        {box.x0 == 0 ? "symmetry_x" : "left", 0, box.x0},
                        {"right", 0, box.x1},
                        {box.y0 == 0 ? "symmetry_y" : "front", 1, box.y0},
                        {"back", 1, box.y1}};
  gmsh::vectorpair faces;
  gmsh::model::getEntities(faces, 2);
  for (const Side& side : sides) {
    std::vector<int> tags;
    for (const auto& [dim, tag] : faces) {
      double low[3], high[3];
      gmsh::model::getBoundingBox(dim, tag, low[0], low[1], low[2], high[0], high[1], high[2]);
      if (std::abs(low[side.axis] - side.at) < 1e-6 && std::abs(high[side.axis] - side.at) < 1e-6) tags.push_back(tag);
    }
    gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, tags), side.name);
  }
  gmsh::model::addPhysicalGroup(3, {volume});

  // Distance to the disc: sqrt(max(0, ρ − r)² + z²) with ρ the distance from its centre's axis.
  // Every number is parenthesised: Gmsh's MathEval misreads "y - -0.1" (the box would get a
  // garbage size field and no elements at all).
  const Eigen::Vector2d c = unit_centre(request);
  char outside[256];
  std::snprintf(outside, sizeof outside,
                "Max(0, Sqrt((x - (%.17g))*(x - (%.17g)) + (y - (%.17g))*(y - (%.17g))) - (%.17g))", c.x(), c.x(),
                c.y(), c.y(), unit_radius(request));
  const std::string distance = "Sqrt(" + std::string(outside) + "*" + outside + " + z*z)";
  if (request.size_field)
    set_size_field(request.size_field, request.height, request.volume_algorithm);
  else
    set_graded_size_expression(unit_sizes(request), distance, request.volume_algorithm);
  gmsh::option::setNumber("Mesh.ElementOrder", request.order);
  gmsh::model::mesh::generate(3);
  throw_if_gmsh_failed();
  Mesh mesh = mesh_from_gmsh(request.height);
  mesh.regions.clear();
  return mesh;
}

}  // namespace contactqp::detail
