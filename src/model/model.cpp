// From a scene to a model: the candidate distance, the mesh graded towards where contact can
// happen, boundary conditions, and the contact candidates.
#include <algorithm>
#include <cmath>
#include <limits>

#include "../contact/contact.hpp"
#include "../mesh/half_disc_mesher.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/model.hpp"

namespace contactqp {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Candidates are the nodes whose initial gap is at most this many times the largest
// prescribed displacement: the body cannot approach an obstacle by much more than it is
// pushed, and the margin covers the local deformation near the contact zone.
constexpr double kLoadGapFactor = 1.5;

// The candidate distance: the scene's, or one that follows from the load.
void choose_max_gap(const Scene& scene, Model& model) {
  if (scene.contact.max_gap) {
    model.max_gap = *scene.contact.max_gap;
    model.max_gap_rule = "contact.max_gap";
    return;
  }
  double largest = -1;
  for (const LoadSpec& load : scene.loads) {
    if (load.type != "displacement") continue;
    const double ux = load.value[0].value_or(0.0), uy = load.value[1].value_or(0.0);
    largest = std::max(largest, std::hypot(ux, uy));
  }
  if (largest >= 0) {
    model.max_gap = kLoadGapFactor * largest;
    model.max_gap_rule = "1.5 × the largest prescribed displacement";
  } else {
    model.max_gap = std::numeric_limits<double>::infinity();
    model.max_gap_rule = "every boundary node facing an obstacle";
  }
}

// The arc of the half disc (angles φ, see half_disc_mesher.hpp) where contact can happen:
// the facing points within max_gap of an obstacle, widened by one contact element on each
// side. When no point qualifies, the single point closest to an obstacle.
std::pair<double, double> fine_arc(const Scene& scene, double max_gap) {
  const double R = scene.body.radius;
  const double start = scene.body.symmetry ? 0.0 : -kPi / 2, end = kPi / 2;
  const int samples = 20000;
  double from = std::numeric_limits<double>::infinity(), to = -from;
  double closest_phi = 0, closest_gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double phi = start + (end - start) * k / samples;
    const Eigen::Vector2d x(R * std::sin(phi), R - R * std::cos(phi));
    const Eigen::Vector2d outward(std::sin(phi), -std::cos(phi));
    for (const ObstacleSpec& obstacle : scene.obstacles) {
      const detail::ObstacleProjection p = detail::project(obstacle, x);
      if (outward.dot(p.normal) >= -1e-9) continue;
      if (p.gap < closest_gap) {
        closest_gap = p.gap;
        closest_phi = phi;
      }
      if (p.gap <= max_gap) {
        from = std::min(from, phi);
        to = std::max(to, phi);
      }
    }
  }
  if (from > to) return {closest_phi, closest_phi};
  const double widen = scene.body.mesh.contact_size / R;
  return {std::max(start, from - widen), std::min(end, to + widen)};
}

// Prescribes DOF `dof` to `value`; a second, different value for the same DOF is an error.
void prescribe(Model& model, int dof, double value, const std::string& field) {
  if (model.free_index[dof] == -1 && model.prescribed[dof] != value) {
    const double scale = std::max(std::abs(value), std::abs(model.prescribed[dof]));
    if (std::abs(model.prescribed[dof] - value) > 1e-12 * scale)
      throw InputError(field, "= " + detail::format_value(value) + " conflicts with " +
                                  detail::format_value(model.prescribed[dof]) + " prescribed at node " +
                                  std::to_string(dof / 2) + " by another condition");
  }
  model.free_index[dof] = -1;
  model.prescribed[dof] = value;
}

}  // namespace

Model build_model(const Scene& scene, const BuildOptions& options) {
  Model model;
  model.scene = scene;
  choose_max_gap(scene, model);

  Stopwatch clock;
  detail::HalfDiscMeshRequest request;
  request.radius = scene.body.radius;
  request.symmetry = scene.body.symmetry;
  request.size = scene.body.mesh.size;
  request.contact_size = scene.body.mesh.contact_size;
  request.grading = scene.body.mesh.grading;
  request.order = scene.body.mesh.order;
  std::tie(request.fine_from, request.fine_to) = fine_arc(scene, model.max_gap);
  const double estimate = detail::estimate_half_disc_triangles(request);
  if (estimate > static_cast<double>(options.max_elements))
    throw InputError("body.mesh", "would have about " + std::to_string(static_cast<long long>(estimate)) +
                                      " triangles, more than the limit of " + std::to_string(options.max_elements) +
                                      "; coarsen body.mesh.size or contact_size, or raise --max-elements");
  try {
    model.mesh = detail::mesh_half_disc(request);
  } catch (const std::exception& error) {
    throw InputError("body.mesh", std::string("could not be meshed: ") + error.what());
  } catch (...) {
    throw InputError("body.mesh", "could not be meshed (Gmsh failed)");
  }
  if (model.mesh.n_elements() > options.max_elements)
    throw InputError("body.mesh", "has " + std::to_string(model.mesh.n_elements()) + " triangles, more than the limit of " +
                                      std::to_string(options.max_elements) + "; raise --max-elements");
  model.timings.add("mesh", clock.seconds());

  clock.restart();
  const int n_dofs = 2 * model.mesh.n_nodes();
  model.free_index.assign(n_dofs, 0);
  model.prescribed = Eigen::VectorXd::Zero(n_dofs);
  for (size_t l = 0; l < scene.loads.size(); ++l) {
    const LoadSpec& load = scene.loads[l];
    const std::string field = scene.loads.size() == 1 ? "load.value" : "load[" + std::to_string(l) + "].value";
    for (int node : boundary_nodes(model.mesh, load.boundary))
      for (int c = 0; c < 2; ++c)
        if (load.value[c]) prescribe(model, 2 * node + c, *load.value[c], field);
  }
  if (scene.body.symmetry)
    for (int node : boundary_nodes(model.mesh, "symmetry")) prescribe(model, 2 * node, 0.0, "body.symmetry");
  for (int& index : model.free_index)
    if (index == 0) index = model.n_free++;
    else index = -1;

  model.candidates = detail::select_candidates(model.mesh, scene.obstacles, scene.contact.boundary, model.max_gap);
  detail::remove_prescribed_candidates(model);

  if (scene.model == PlaneModel::PlaneStrain && scene.material.nu > 0.45 && scene.body.mesh.order == 1)
    model.warnings.push_back("material.nu = " + detail::format_value(scene.material.nu) +
                             " with linear triangles in plane strain: they lock as ν → 0.5 and understate the "
                             "compliance; use \"order\": 2 under body.mesh");
  model.timings.add("model", clock.seconds());
  return model;
}

}  // namespace contactqp
