// Hertz's contact (docs/architecture.md), with the radius of relative curvature
// 1/R = 1/R_body + 1/R_obstacle:
//   2D, two cylinders (plane strain or stress):  b = sqrt(4 P R / (π E*)),  p0 = 2P / (π b),
//                                                p(x) = p0 sqrt(1 − x²/b²);
//   3D, two spheres:                             a = (3 P R / (4 E*))^(1/3),  p0 = 3P / (2π a²),
//                                                p(r) = p0 sqrt(1 − r²/a²).
#include <algorithm>
#include <cmath>
#include <map>

#include "contact/contact.hpp"
#include "contactqp/post.hpp"
#include "fitted_curvature.hpp"
#include "qp/pi.hpp"

namespace contactqp {
namespace {

// Gauss–Legendre, 8 points on [−1, 1].
const double kNodes[] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                         0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
const double kWeights[] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                           0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

}  // namespace

double interpolated_pressure(const std::vector<ContactProfilePoint>& profile, double s) {
  if (profile.empty() || s < profile.front().s || s > profile.back().s) return 0.0;
  auto upper = std::lower_bound(profile.begin(), profile.end(), s,
                                [](const ContactProfilePoint& p, double value) { return p.s < value; });
  if (upper == profile.begin()) return upper->pressure;
  const auto lower = upper - 1;
  const double t = (s - lower->s) / (upper->s - lower->s);
  return (1 - t) * lower->pressure + t * upper->pressure;
}

double hertz_pressure(const HertzComparison& hertz, double x) {
  const double b = hertz.dim == 3 ? hertz.contact_radius : hertz.half_width;
  if (!(b > 0) || std::abs(x) >= b) return 0.0;
  return hertz.max_pressure * std::sqrt(1.0 - (x / b) * (x / b));
}

namespace {

// Signed curvature of the body's boundary through the nodes in contact with obstacle o (positive
// when convex towards it), fitted through their initial positions (fitted_curvature.hpp).
std::optional<double> fitted_body_curvature(const Model& model, const ObstacleContact& contact) {
  std::vector<Eigen::Vector3d> points;
  double most = 1e-300;
  for (const ContactProfilePoint& p : contact.profile) most = std::max(most, p.force);
  for (const ContactProfilePoint& p : contact.profile)
    if (p.force > 1e-8 * most) points.push_back(model.mesh.nodes[p.node]);
  if (points.empty()) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : points) mean += x;
  mean /= static_cast<double>(points.size());
  const Eigen::Vector3d towards_obstacle = -detail::project(model.scene.obstacles[contact.obstacle], mean).normal;
  return fitted_curvature(points, model.dim, towards_obstacle);
}

// 1/R = body curvature + obstacle curvature, and the words for where it came from.
std::optional<std::pair<double, std::string>> relative_curvature(const Model& model, const ObstacleContact& contact) {
  const Scene& scene = model.scene;
  const ObstacleSpec& obstacle = scene.obstacles[contact.obstacle];
  if (obstacle.is<ProfileObstacle>() || obstacle.is<PunchObstacle>()) return std::nullopt;
  const std::optional<double> curved = detail::obstacle_curvature(obstacle);
  if (!curved) return std::nullopt;  // a cylinder: the zone is elliptical, not Hertz's circle
  const double obstacle_curvature = *curved;
  double body_curvature = 0;
  std::string source;
  if ((scene.body.shape == "half_disc" && scene.contact.boundary == "arc") ||
      (scene.body.shape == "hemisphere" && scene.contact.boundary == "surface")) {
    body_curvature = 1.0 / scene.body.radius;
    source = "body.radius";
  } else if (scene.body.shape == "mesh") {
    const auto fitted = fitted_body_curvature(model, contact);
    if (!fitted) return std::nullopt;
    body_curvature = *fitted;
    source = "fitted";
  }
  if (obstacle_curvature > 0) source += source.empty() ? "obstacle.radius" : " and obstacle.radius";
  const double curvature = body_curvature + obstacle_curvature;
  // A flat body on a plane (or a curvature lost in the fit's noise) is not Hertz's problem.
  const double zone = model.dim == 3 ? contact.contact_radius : contact.half_width;
  if (!(curvature > 0) || curvature * std::max(zone, 1e-300) < 1e-6) return std::nullopt;
  return std::make_pair(curvature, source);
}

}  // namespace

std::optional<HertzComparison> compare_with_hertz(const Model& model, const ContactSummary& contact) {
  if (contact.obstacles.size() != 1) return std::nullopt;
  return compare_with_hertz(model, contact.obstacles[0]);
}

namespace {

// Two spheres (3D): a, p0 and the L2 error of p(r) by nodal quadrature over the candidates
// (their tributary areas cover the Hertz disc), against the exact ∫ p_Hertz² dA = π a² p0²/2.
std::optional<HertzComparison> compare_with_hertz_3d(const Model& model, const ObstacleContact& contact) {
  const Scene& scene = model.scene;
  const double P = contact.resultant.norm();
  if (!(P > 0)) return std::nullopt;
  const auto curvature = relative_curvature(model, contact);
  if (!curvature) return std::nullopt;
  HertzComparison hertz;
  hertz.dim = 3;
  const double E = scene.material.E, nu = scene.material.nu, R = 1.0 / curvature->first;
  hertz.radius = R;
  hertz.radius_source = curvature->second;
  hertz.effective_modulus = E / (1 - nu * nu);
  hertz.force = P;
  hertz.contact_radius = std::cbrt(3 * P * R / (4 * hertz.effective_modulus));
  hertz.max_pressure = 3 * P / (2 * kPi * hertz.contact_radius * hertz.contact_radius);
  hertz.error_contact_radius = (contact.contact_radius - hertz.contact_radius) / hertz.contact_radius;
  hertz.error_max_pressure = (contact.max_pressure - hertz.max_pressure) / hertz.max_pressure;
  std::map<int, double> tributary;
  for (const Candidate& c : model.candidates)
    if (c.obstacle == contact.obstacle) tributary[c.node] = c.tributary;
  double error = 0;
  for (const ContactProfilePoint& point : contact.profile) {
    const double difference = point.pressure - hertz_pressure(hertz, point.s);
    error += tributary[point.node] * difference * difference;
  }
  const double copies = mirror_copies(model);
  const double a = hertz.contact_radius;
  const double reference = kPi * a * a * hertz.max_pressure * hertz.max_pressure / 2 / copies;
  hertz.error_l2 = std::sqrt(error / reference);
  return hertz;
}

}  // namespace

std::optional<HertzComparison> compare_with_hertz(const Model& model, const ObstacleContact& contact) {
  if (model.dim == 3) return compare_with_hertz_3d(model, contact);
  const Scene& scene = model.scene;
  // Hertz's P: the resultant pressing the bodies together, per length (on a curved obstacle a
  // little less than Σλ, whose normals fan out).
  const double P = contact.resultant.norm() / scene.body.thickness;
  if (!(P > 0)) return std::nullopt;
  const auto curvature = relative_curvature(model, contact);
  if (!curvature) return std::nullopt;

  HertzComparison hertz;
  const double E = scene.material.E, nu = scene.material.nu, R = 1.0 / curvature->first;
  hertz.radius = R;
  hertz.radius_source = curvature->second;
  hertz.effective_modulus = scene.model == PlaneModel::PlaneStrain ? E / (1 - nu * nu) : E;
  hertz.force = P;
  hertz.half_width = std::sqrt(4 * P * R / (kPi * hertz.effective_modulus));
  hertz.max_pressure = 2 * P / (kPi * hertz.half_width);
  hertz.error_half_width = (contact.half_width - hertz.half_width) / hertz.half_width;
  hertz.error_max_pressure = (contact.max_pressure - hertz.max_pressure) / hertz.max_pressure;

  // L2 error over the union of the Hertz zone and the candidates, split at every profile
  // point and at the ends of the Hertz zone, where the integrand has kinks.
  const auto& profile = contact.profile;
  const double c = contact.centre, b = hertz.half_width;
  const bool half = scene.body.symmetry;
  std::vector<double> breaks = {half ? std::max(0.0, c) : c - b, c + b};
  for (const ContactProfilePoint& point : profile) breaks.push_back(point.s);
  std::sort(breaks.begin(), breaks.end());
  const double lo = half ? 0.0 : breaks.front();
  double error = 0;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = std::max(lo, breaks[k]), z = breaks[k + 1];
    if (!(z > a)) continue;
    for (int q = 0; q < 8; ++q) {
      const double s = 0.5 * (a + z) + 0.5 * (z - a) * kNodes[q];
      const double difference = interpolated_pressure(profile, s) - hertz_pressure(hertz, s - c);
      error += 0.5 * (z - a) * kWeights[q] * difference * difference;
    }
  }
  // ∫ p_Hertz² over the zone is (4/3) p0² b, half of it with symmetry.
  const double reference = (half ? 2.0 / 3.0 : 4.0 / 3.0) * hertz.max_pressure * hertz.max_pressure * b;
  hertz.error_l2 = std::sqrt(error / reference);
  return hertz;
}

}  // namespace contactqp
