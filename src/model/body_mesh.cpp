// The body's mesh: the generated shapes refined along the part of the contact boundary that
// faces an obstacle within the candidate distance, or a Gmsh file as it is.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "contact/contact.hpp"
#include "contactqp/errors.hpp"
#include "mesh/gmsh_plugin.hpp"
#include "model_parts.hpp"
#include "qp/pi.hpp"

namespace contactqp::detail {
namespace {

// A boundary curve x(t), t ∈ [t0, t1], with its outward unit normal.
struct Curve {
  std::function<Eigen::Vector3d(double)> point, outward;
  double t0 = 0, t1 = 1;
};

// The parameters where the curve faces an obstacle within max_gap: each maximal run of such
// samples, widened by `widen` on each side, overlapping runs merged. When no point
// qualifies, the single point closest to an obstacle it faces.
Intervals fine_intervals(const Curve& curve, const std::vector<ObstacleSpec>& obstacles, double max_gap, double widen) {
  const int samples = 20000;
  Intervals runs;
  bool in_run = false;
  double closest_t = curve.t0, closest_gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double t = curve.t0 + (curve.t1 - curve.t0) * k / samples;
    const Eigen::Vector3d x = curve.point(t), outward = curve.outward(t);
    bool near = false;
    for (const ObstacleSpec& obstacle : obstacles) {
      const ObstacleProjection p = project(obstacle, x);
      if (outward.dot(p.normal) >= -1e-9) continue;
      if (p.gap < closest_gap) {
        closest_gap = p.gap;
        closest_t = t;
      }
      near = near || p.gap <= max_gap;
    }
    if (near && !in_run) runs.emplace_back(t, t);
    if (near) runs.back().second = t;
    in_run = near;
  }
  if (runs.empty()) return {{closest_t, closest_t}};
  Intervals merged;
  for (const auto& [from, to] : runs) {
    const double a = std::max(curve.t0, from - widen), b = std::min(curve.t1, to + widen);
    if (!merged.empty() && a <= merged.back().second)
      merged.back().second = std::max(merged.back().second, b);
    else
      merged.emplace_back(a, b);
  }
  return merged;
}

void refuse_oversized(double estimate, const BuildOptions& options, const std::string& what = "triangles") {
  // Written so that a NaN estimate is refused too; sizes that underflow give +inf.
  if (!(estimate <= static_cast<double>(options.max_elements)))
    throw InputError("body.mesh", "would have " +
                                      (std::isfinite(estimate) ? "about " + format_value(std::round(estimate))
                                                               : std::string("unboundedly many")) +
                                      " " + what + ", more than the limit of " + std::to_string(options.max_elements) +
                                      "; coarsen body.mesh.size or contact_size, or raise --max-elements");
}

// Gmsh errors while meshing a generated shape are bad input too (sizes it cannot honour).
template <class Mesher>
auto generate(const Mesher& mesher) -> decltype(mesher()) {
  try {
    return mesher();
  } catch (const std::exception& error) {
    throw InputError("body.mesh", std::string("could not be meshed: ") + error.what());
  } catch (...) {
    throw InputError("body.mesh", "could not be meshed: " + gmsh_plugin().gmsh_error_text());
  }
}

// The fields both generated shapes' requests share.
template <class Request>
void copy_mesh_spec(const BodySpec& body, Request& request) {
  request.symmetry = body.symmetry;
  request.size = body.mesh.size;
  request.contact_size = body.mesh.contact_size;
  request.grading = body.mesh.grading;
  request.order = body.mesh.order;
  request.size_field = body.mesh.size_field;
}

// A request with a size field is sized by it, not graded: the graded count would be no guide.
// Its caller (an adaptive run) predicts the count from the field; the mesh is checked after.
void refuse_oversized_graded(double estimate, const SizeField& size_field, const BuildOptions& options,
                             const std::string& what = "triangles") {
  if (!size_field) refuse_oversized(estimate, options, what);
}

CoarseMesh coarse_half_disc_body(const Scene& scene, double max_gap, const BuildOptions& options) {
  const BodySpec& body = scene.body;
  HalfDiscMeshRequest request;
  request.radius = body.radius;
  copy_mesh_spec(body, request);
  request.refinements = body.mesh.size_field ? 0 : body.mesh.refinements;
  // The arc P(φ) = (R sin φ, R − R cos φ); see half_disc_mesher.hpp.
  const double R = body.radius;
  Curve arc{[R](double phi) { return Eigen::Vector3d(R * std::sin(phi), R - R * std::cos(phi), 0.0); },
            [](double phi) { return Eigen::Vector3d(std::sin(phi), -std::cos(phi), 0.0); },
            body.symmetry ? 0.0 : -kPi / 2, kPi / 2};
  request.fine = fine_intervals(arc, scene.obstacles, max_gap, body.mesh.contact_size / R);
  refuse_oversized_graded(gmsh_plugin().estimate_half_disc_triangles(request), request.size_field, options);
  return generate([&] { return gmsh_plugin().coarse_half_disc(request); });
}

Mesh mesh_rectangle_body(const Scene& scene, double max_gap, const BuildOptions& options) {
  const BodySpec& body = scene.body;
  RectangleMeshRequest request;
  request.width = body.width;
  request.height = body.height;
  copy_mesh_spec(body, request);
  request.fine_side = scene.contact.boundary;
  for (const RectangleSide& side : gmsh_plugin().rectangle_sides(body.width, body.height, body.symmetry)) {
    if (side.name != request.fine_side) continue;
    const Eigen::Vector3d a(side.a.x(), side.a.y(), 0.0), d(side.b.x() - side.a.x(), side.b.y() - side.a.y(), 0.0);
    const Eigen::Vector3d outward = Eigen::Vector3d(d.y(), -d.x(), 0.0).normalized();
    Curve line{[a, d](double t) { return Eigen::Vector3d(a + t * d); }, [outward](double) { return outward; }};
    request.fine = fine_intervals(line, scene.obstacles, max_gap, body.mesh.contact_size / d.norm());
  }
  refuse_oversized_graded(gmsh_plugin().estimate_rectangle_triangles(request), request.size_field, options);
  return generate([&] { return gmsh_plugin().mesh_rectangle(request); });
}

// The radius, around the lowest point of a body's contact face (the origin), within which it may
// touch: the farthest sample of the surface (a cap of the hemisphere, a disc of the box's bottom)
// that faces an obstacle within max_gap, widened by `widen`. With no such sample, `widen` alone:
// the generated bodies are made to touch first at the origin.
double fine_radius(const std::function<Eigen::Vector3d(double, double)>& surface,
                   const std::function<Eigen::Vector3d(double, double)>& outward, double r_max,
                   const std::vector<ObstacleSpec>& obstacles, double max_gap, double widen) {
  const int rings = 400, spokes = 24;
  double reach = 0;
  for (int i = 0; i <= rings; ++i) {
    const double r = r_max * i / rings;
    for (int k = 0; k < spokes; ++k) {
      const double angle = 2 * kPi * k / spokes;
      const Eigen::Vector3d x = surface(r, angle), n = outward(r, angle);
      for (const ObstacleSpec& obstacle : obstacles) {
        const ObstacleProjection p = project(obstacle, x);
        if (n.dot(p.normal) < -1e-9 && p.gap <= max_gap) reach = std::max(reach, r);
      }
    }
  }
  return std::min(r_max, reach + widen);
}

CoarseMesh coarse_hemisphere_body(const Scene& scene, double max_gap, const BuildOptions& options) {
  const BodySpec& body = scene.body;
  HemisphereMeshRequest request;
  request.radius = body.radius;
  copy_mesh_spec(body, request);
  request.symmetry_x = body.symmetry_x;
  request.symmetry_y = body.symmetry_y;
  request.refinements = body.mesh.size_field ? 0 : body.mesh.refinements;
  // The sphere's lower half seen from its lowest point: at horizontal distance r, direction θ.
  const double R = body.radius;
  auto surface = [R](double r, double angle) {
    return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), R - std::sqrt(std::max(0.0, R * R - r * r)));
  };
  auto outward = [R, surface](double r, double angle) {
    return Eigen::Vector3d((surface(r, angle) - Eigen::Vector3d(0, 0, R)) / R);
  };
  request.fine_radius = fine_radius(surface, outward, R, scene.obstacles, max_gap, body.mesh.contact_size);
  refuse_oversized_graded(gmsh_plugin().estimate_hemisphere_elements(request), request.size_field, options,
                          "tetrahedra");
  return generate([&] { return gmsh_plugin().coarse_hemisphere(request); });
}

Mesh mesh_box_body(const Scene& scene, double max_gap, const BuildOptions& options) {
  const BodySpec& body = scene.body;
  BoxMeshRequest request;
  request.width = body.width;
  request.depth = body.depth;
  request.height = body.height;
  copy_mesh_spec(body, request);
  request.symmetry_x = body.symmetry_x;
  request.symmetry_y = body.symmetry_y;
  // The contact face is the bottom z = 0 (the only one the box's scenes press so far).
  auto surface = [](double r, double angle) { return Eigen::Vector3d(r * std::cos(angle), r * std::sin(angle), 0.0); };
  auto outward = [](double, double) { return Eigen::Vector3d(0, 0, -1); };
  const double r_max = 0.5 * std::hypot(body.width, body.depth);
  request.fine_radius = fine_radius(surface, outward, r_max, scene.obstacles, max_gap, body.mesh.contact_size);
  // A punch centred on the bottom face: its rim circle becomes a line of the mesh, so the
  // pressure's singular edge falls on nodes (one punch; several leave the face as it is).
  int punches = 0;
  for (const ObstacleSpec& obstacle : scene.obstacles)
    if (const auto* punch = obstacle.as<PunchObstacle>()) {
      const bool centred = punch->center.head<2>().norm() <= 1e-12 * body.width &&
                           std::abs(punch->center.z()) <= 1e-12 * body.height &&
                           std::abs(std::abs(punch->axis.z()) - 1) <= 1e-12;
      if (centred && ++punches == 1) request.rim_radius = punch->radius;
    }
  if (punches > 1) request.rim_radius = 0;
  refuse_oversized_graded(gmsh_plugin().estimate_box_elements(request), request.size_field, options, "tetrahedra");
  return generate([&] { return gmsh_plugin().mesh_box(request); });
}

}  // namespace

CoarseMesh coarse_body_mesh(const Scene& scene, double max_gap, const BuildOptions& options) {
  CoarseMesh coarse;
  if (scene.body.shape == "half_disc")
    coarse = coarse_half_disc_body(scene, max_gap, options);
  else if (scene.body.shape == "rectangle")
    coarse.mesh = mesh_rectangle_body(scene, max_gap, options);
  else if (scene.body.shape == "hemisphere")
    coarse = coarse_hemisphere_body(scene, max_gap, options);
  else if (scene.body.shape == "box")
    coarse.mesh = mesh_box_body(scene, max_gap, options);
  else
    coarse.mesh = read_gmsh_file({scene.body.file, scene.body.mesh.order, scene.body.mesh.size_factor});
  if (coarse.refinements == 0) coarse.order = coarse.mesh.order;
  const Mesh& mesh = coarse.mesh;
  if (scene.body.formulation == Formulation::Mixed && coarse.order != 2)
    throw InputError("body.formulation", "= \"mixed\": needs 6-node triangles, and " + scene.body.file +
                                             " holds 3-node ones (mesh it with gmsh -order 2)");
  if (mesh.dim != scene.dim())
    throw InputError(scene.body.file,
                     "holds a " + std::to_string(mesh.dim) + "D mesh (" + to_string(mesh.type()) +
                         " elements), but \"model\": \"" + to_string(scene.model) + "\" is " +
                         std::to_string(scene.dim()) + "D" +
                         (mesh.dim == 3 ? "; use \"model\": \"solid\"" : "; use plane_strain or plane_stress"));
  const long long n_elements = mesh.n_elements() * refined_children(mesh.dim, coarse.refinements);
  if (n_elements > options.max_elements)
    throw InputError("body.mesh", "has " + std::to_string(n_elements) + (mesh.dim == 2 ? " triangles" : " tetrahedra") +
                                      ", more than the limit of " + std::to_string(options.max_elements) +
                                      "; raise --max-elements");
  return coarse;
}

CoarseMesh body_refinement(const Scene& scene) {
  CoarseMesh how;
  const BodySpec& body = scene.body;
  if (body.mesh.refinements == 0 || body.mesh.size_field || (body.shape != "half_disc" && body.shape != "hemisphere"))
    return how;
  how.refinements = body.mesh.refinements;
  how.order = body.mesh.order;
  how.snap = body.shape == "half_disc" ? gmsh_plugin().half_disc_snap() : gmsh_plugin().hemisphere_snap();
  how.scale = body.radius;
  return how;
}

Mesh refine_body_mesh(const CoarseMesh& coarse, const Mesh& part, NodeParents* parents) {
  return generate([&] { return refine_coarse(coarse, part, parents); });
}

Mesh mesh_body(const Scene& scene, double max_gap, const BuildOptions& options) {
  const CoarseMesh coarse = coarse_body_mesh(scene, max_gap, options);
  return refine_body_mesh(coarse, coarse.mesh);
}

}  // namespace contactqp::detail
