// Friction at the contact rows (docs/friction.md): the friction force, traction and slip at
// each row, its state (gap, stick, slip), and per contact zone the tangential resultant, the
// stick zone and, where it applies, Cattaneo–Mindlin's solution.
#include <algorithm>
#include <cmath>

#include "contact/contact.hpp"
#include "contactqp/post.hpp"
#include "qp/pi.hpp"

namespace contactqp {
namespace {

// A loaded row slips when it moved in this step — its slip above this fraction of the largest
// row's (a stuck row's slip is the solver's tolerance: 3e-8 of it on
// scenes/mindlin-cylinders.json at tol 1e-8, the first slipping row's 1e-3) — or when its
// multiplier is on its bound. The slip decides: Coulomb's fixed point leaves λ_T a relative 1e-6
// inside the bound μλ_N of the last λ_N, more at the zone's edge where λ_N is small, while
// Mindlin's traction nears the bound only like sqrt(c − r) from inside the stick zone.
constexpr double kMoved = 1e-5;
constexpr double kOnBound = 1e-6;
// When every row sticks the largest slip is round-off (1e-20 on scenes/mindlin-cylinders.json
// with μ = 100) and no scale: a row moved only if its slip is also above this fraction of the
// largest displacement (stuck rows 1e-14, the first slipping row 4e-10 on the cylinders, whose
// displacements are 2.5e-5).
constexpr double kMovedOfDisplacement = 1e-8;

// The friction, stick zone and Mindlin comparison of the rows `rows` (one obstacle's or pair's);
// `profile` gives each row's coordinate, `centre` the 2D zone's centre.
FrictionZone zone_of(const Model& model, const FrictionFields& fields, const std::vector<ContactProfilePoint>& profile,
                     double centre, const HertzComparison* hertz, const Material& body, const Material* other) {
  FrictionZone zone;
  const int dim = model.dim;
  double stick = 0;
  double coefficient = -1;  // the rows' μ when they share one, else NaN
  const FrictionSpec* first = nullptr;
  for (const ContactProfilePoint& point : profile) {
    const int i = point.row;
    zone.resultant += fields.force[i];
    if (fields.state[i] == 1) {
      ++zone.stick_nodes;
      stick += model.candidates[i].tributary;
    } else if (fields.state[i] == 2) {
      ++zone.slip_nodes;
    }
    const FrictionSpec* spec = detail::friction_of(model, model.candidates[i]);
    if (!first) first = spec;
    const double mu = spec && spec->law == FrictionLaw::Coulomb ? spec->coefficient : NAN;
    coefficient = coefficient < 0 ? mu : (mu == coefficient ? mu : NAN);
  }
  zone.resultant = whole_body_sum(model, zone.resultant);
  zone.tangential_force = zone.resultant.norm();
  stick *= mirror_copies(model);
  zone.stick_size = dim == 2 ? stick / 2 : std::sqrt(stick / kPi);
  if (hertz && std::isfinite(coefficient) && coefficient > 0)
    zone.mindlin = compare_with_mindlin(model, fields, profile, centre, *hertz, coefficient, zone, body, other);
  return zone;
}

}  // namespace

FrictionFields friction_fields(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& u,
                               const Eigen::VectorXd& lambda, const Eigen::VectorXd& lambda_t) {
  const FrictionBlock& block = qp.friction;
  const int m = qp.n_constraints(), nd = block.n_directions, dim = model.dim;
  FrictionFields fields;
  fields.force.assign(m, Eigen::Vector3d::Zero());
  fields.traction.assign(m, Eigen::Vector3d::Zero());
  fields.slip.assign(m, Eigen::Vector3d::Zero());
  fields.state.assign(m, 0);
  fields.bound.assign(m, 0.0);
  const Eigen::VectorXd slip = block.T * u - block.offset;
  const double loaded = 1e-8 * (lambda.size() ? lambda.maxCoeff() : 0.0);
  double largest_slip = 0;
  for (int i = 0; i < m; ++i)
    if (lambda[i] > loaded) largest_slip = std::max(largest_slip, slip.segment(i * nd, nd).norm());
  const double still = kMovedOfDisplacement * (u.size() ? u.cwiseAbs().maxCoeff() : 0.0);
  for (int i = 0; i < m; ++i) {
    const Candidate& c = model.candidates[i];
    const std::vector<Eigen::Vector3d> t = detail::row_tangents(model, c);
    for (int k = 0; k < nd; ++k) {
      fields.force[i] -= lambda_t[i * nd + k] * t[k];
      fields.slip[i] += slip[i * nd + k] * t[k];
    }
    fields.bound[i] = block.law == FrictionLaw::Tresca ? block.threshold[i] : block.coefficient[i] * lambda[i];
    if (!(lambda[i] > loaded)) continue;  // gap
    const bool moved = slip.segment(i * nd, nd).norm() > std::max(kMoved * largest_slip, still);
    const bool on_bound =
        !(fields.bound[i] > 0) || lambda_t.segment(i * nd, nd).norm() >= (1 - kOnBound) * fields.bound[i];
    fields.state[i] = moved || on_bound ? 2 : 1;
  }
  for (int component = 0; component < dim; ++component) {
    Eigen::VectorXd along(m);
    for (int i = 0; i < m; ++i) along[i] = fields.force[i][component];
    const std::vector<double> traction = nodal_pressures(model, qp, along);
    for (int i = 0; i < m; ++i) fields.traction[i][component] = traction[i];
  }
  return fields;
}

Eigen::VectorXd friction_nodal_forces(const Model& model, const QuadraticProgram& qp, const Eigen::VectorXd& lambda_t) {
  const int dim = model.dim, nd = qp.friction.n_directions;
  Eigen::VectorXd force = Eigen::VectorXd::Zero(dim * model.mesh.n_nodes());
  if (qp.friction.empty() || lambda_t.size() == 0) return force;
  for (int i = 0; i < qp.n_constraints(); ++i) {
    const Candidate& c = model.candidates[i];
    const std::vector<Eigen::Vector3d> t = detail::row_tangents(model, c);
    Eigen::Vector3d on_node = Eigen::Vector3d::Zero();
    for (int k = 0; k < nd; ++k) on_node -= lambda_t[i * nd + k] * t[k];
    force.segment(dim * c.node, dim) += on_node.head(dim);
    for (int j = 0; j < c.n_face_nodes; ++j)
      force.segment(dim * c.face_nodes[j], dim) -= c.weights[j] * on_node.head(dim);
  }
  return force;
}

void summarize_friction(const Model& model, const FrictionFields& fields, ContactSummary& contact,
                        std::vector<PairContact>& pairs) {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (ObstacleContact& obstacle : contact.obstacles) {
    const auto hertz = compare_with_hertz(model, obstacle);
    obstacle.friction = zone_of(model, fields, obstacle.profile, obstacle.centre, hertz ? &*hertz : nullptr,
                                model.scene.material, nullptr);
    total += obstacle.friction->resultant;
  }
  contact.tangential_force = total.norm();
  if (!contact.obstacles.empty()) contact.stick_size = contact.obstacles[contact.main_obstacle].friction->stick_size;
  for (PairContact& pair : pairs) {
    const Material& node = model.bodies[pair.node_body].scene.material;
    const Material& face = model.bodies[pair.face_body].scene.material;
    pair.friction = zone_of(model, fields, pair.profile, pair.centre, pair.hertz ? &*pair.hertz : nullptr, node, &face);
  }
}

}  // namespace contactqp
