#include "half_disc_mesher.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <unordered_map>

namespace contactqp::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Area of an equilateral triangle of side h is kTriangleArea · h².
constexpr double kTriangleArea = 0.4330127018922193;

// Gmsh keeps global state: one mesh at a time per process.
std::mutex gmsh_mutex;

struct GmshSession {
  GmshSession() {
    gmsh::initialize();
    gmsh::option::setNumber("General.Terminal", 0);  // silent: contactqp reports, Gmsh does not
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
};

// Boundary edges of Gmsh line elements of the given curves, in compact node numbering.
std::vector<BoundaryEdge> edges_of(const std::vector<int>& curves, int order,
                                   const std::unordered_map<std::size_t, int>& index_of) {
  std::vector<BoundaryEdge> edges;
  const int line_type = order == 1 ? 1 : 8;  // 2-node or 3-node line
  for (int curve : curves) {
    std::vector<std::size_t> tags, node_tags;
    gmsh::model::mesh::getElementsByType(line_type, tags, node_tags, curve);
    const int per = order == 1 ? 2 : 3;
    for (std::size_t k = 0; k + per <= node_tags.size(); k += per) {
      BoundaryEdge edge;
      edge.a = index_of.at(node_tags[k]);
      edge.b = index_of.at(node_tags[k + 1]);
      if (order == 2) edge.mid = index_of.at(node_tags[k + 2]);
      edges.push_back(edge);
    }
  }
  return edges;
}

}  // namespace

double estimate_half_disc_triangles(const HalfDiscMeshRequest& request) {
  // Work in units of R. The size grows linearly with the distance d from the fine arc; the
  // band of the body at distance in [d, d + dd] has area about (ℓ + π d) dd, capped by the
  // body's area.
  const double R = request.radius;
  const double cs = request.contact_size / R, h = request.size / R, gamma = request.grading;
  const double area = request.symmetry ? kPi / 4 : kPi / 2;
  const double arc = std::max(0.0, request.fine_to - request.fine_from);
  double covered = 0, triangles = 0;
  const double d_max = std::max(0.0, (h - cs) / gamma);
  const int steps = 400;
  for (int k = 0; k < steps && covered < area; ++k) {
    const double d0 = d_max * k / steps, d1 = d_max * (k + 1) / steps;
    const double d = 0.5 * (d0 + d1);
    const double band = std::min((arc + kPi * d) * (d1 - d0), area - covered);
    const double local = cs + gamma * d;
    triangles += band / (kTriangleArea * local * local);
    covered += band;
  }
  triangles += std::max(0.0, area - covered) / (kTriangleArea * h * h);
  return triangles;
}

Mesh mesh_half_disc(const HalfDiscMeshRequest& request) {
  std::lock_guard<std::mutex> lock(gmsh_mutex);
  // Mesh the unit geometry and scale afterwards: the mesh of a scaled scene is then exactly
  // the scaled mesh (Gmsh's geometric tolerances are absolute).
  const double R = request.radius;
  const double size = request.size / R, contact_size = request.contact_size / R;
  const double phi_start = request.symmetry ? 0.0 : -kPi / 2, phi_end = kPi / 2;
  const double fine_from = std::clamp(request.fine_from, phi_start, phi_end);
  const double fine_to = std::clamp(request.fine_to, phi_start, phi_end);

  GmshSession session;
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
  gmsh::model::addPhysicalGroup(1, arcs);
  gmsh::model::addPhysicalGroup(1, {top});
  if (symmetry_line >= 0) gmsh::model::addPhysicalGroup(1, {symmetry_line});
  gmsh::model::addPhysicalGroup(2, {surface});

  // Size field: contact_size on the fine arc, growing by `grading` per unit distance from it.
  namespace field = gmsh::model::mesh::field;
  const int distance = field::add("Distance");
  if (!fine_arcs.empty()) {
    std::vector<double> curve_list(fine_arcs.begin(), fine_arcs.end());
    field::setNumbers(distance, "CurvesList", curve_list);
    const double fine_length = fine_to - fine_from;
    field::setNumber(distance, "NumPointsPerCurve", std::max(20.0, 4.0 * fine_length / contact_size / fine_arcs.size()));
  } else {
    // No arc can touch: refine at the point closest to the obstacle all the same.
    const int closest = std::lower_bound(breaks.begin(), breaks.end(), fine_from - 1e-9) - breaks.begin();
    field::setNumbers(distance, "PointsList", {static_cast<double>(points[std::min<size_t>(closest, points.size() - 1)])});
  }
  const int size_field = field::add("MathEval");
  char expression[256];
  std::snprintf(expression, sizeof expression, "Min(%.17g, %.17g + %.17g * F%d)", size, contact_size,
                request.grading, distance);
  field::setString(size_field, "F", expression);
  field::setAsBackgroundMesh(size_field);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped triangles
  gmsh::option::setNumber("Mesh.ElementOrder", request.order);
  gmsh::model::mesh::generate(2);

  // Nodes used by triangles, numbered compactly (Gmsh also meshes the arcs' centre point).
  Mesh mesh;
  mesh.order = request.order;
  const int triangle_type = request.order == 1 ? 2 : 9;
  std::vector<std::size_t> element_tags, element_nodes;
  gmsh::model::mesh::getElementsByType(triangle_type, element_tags, element_nodes, surface);
  std::vector<std::size_t> node_tags;
  std::vector<double> coordinates, parametric;
  gmsh::model::mesh::getNodes(node_tags, coordinates, parametric);
  std::unordered_map<std::size_t, std::size_t> position_of;
  for (std::size_t k = 0; k < node_tags.size(); ++k) position_of[node_tags[k]] = k;
  std::unordered_map<std::size_t, int> index_of;
  mesh.elements.reserve(element_nodes.size());
  for (std::size_t tag : element_nodes) {
    auto [it, inserted] = index_of.emplace(tag, static_cast<int>(mesh.nodes.size()));
    if (inserted) {
      const std::size_t k = position_of.at(tag);
      mesh.nodes.emplace_back(R * coordinates[3 * k], R * coordinates[3 * k + 1]);
    }
    mesh.elements.push_back(it->second);
  }
  mesh.boundaries["arc"] = edges_of(arcs, request.order, index_of);
  mesh.boundaries["top"] = edges_of({top}, request.order, index_of);
  if (symmetry_line >= 0) mesh.boundaries["symmetry"] = edges_of({symmetry_line}, request.order, index_of);
  orient(mesh);
  return mesh;
}

}  // namespace contactqp::detail
