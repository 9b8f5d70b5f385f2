// Hertz's contact of two cylinders, or a cylinder and a plane (plane strain or plane stress),
// ARCHITECTURE.md, with the radius of relative curvature 1/R = 1/R_body + 1/R_obstacle:
//   b = sqrt(4 P R / (π E*)),  p0 = 2P / (π b),  p(x) = p0 sqrt(1 − x²/b²).
#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "../contact/contact.hpp"
#include "contactqp/post.hpp"

namespace contactqp {
namespace {

constexpr double kPi = 3.14159265358979323846;

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
  const double b = hertz.half_width;
  if (!(b > 0) || std::abs(x) >= b) return 0.0;
  return hertz.max_pressure * std::sqrt(1.0 - (x / b) * (x / b));
}

namespace {

// Signed curvature of the body's boundary through the nodes in contact with obstacle o
// (positive when convex towards the obstacle): an algebraic circle A|x|² + Dx + Ey + F = 0
// through the initial positions, fitted in centred, scaled coordinates (exact for nodes on a
// circle, 0 for nodes on a line). nullopt with fewer than four nodes in contact.
std::optional<double> fitted_body_curvature(const Model& model, const ObstacleContact& contact) {
  std::vector<Eigen::Vector2d> points;
  const double loaded = 1e-8 * std::max(1e-300, [&] {
    double m = 0;
    for (const auto& p : contact.profile) m = std::max(m, p.force);
    return m;
  }());
  for (const ContactProfilePoint& p : contact.profile)
    if (p.force > loaded) points.push_back(model.mesh.nodes[p.node]);
  if (points.size() < 4) return std::nullopt;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& x : points) mean += x;
  mean /= static_cast<double>(points.size());
  double scale = 0;
  for (const auto& x : points) scale = std::max(scale, (x - mean).norm());
  Eigen::MatrixXd M(points.size(), 4);
  for (size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector2d y = (points[k] - mean) / scale;
    M.row(k) << y.squaredNorm(), y.x(), y.y(), 1.0;
  }
  const Eigen::Vector4d c = Eigen::JacobiSVD<Eigen::MatrixXd>(M, Eigen::ComputeFullV).matrixV().col(3);
  const double A = c[0], D = c[1], E = c[2], F = c[3];
  const double gradient = std::sqrt(std::max(0.0, D * D + E * E - 4 * A * F));  // |∇(A|y|² + Dy + Ey + F)| on the curve
  if (!(gradient > 0)) return std::nullopt;
  // ∇ at the centroid (y = 0) is (D, E); the body is convex when the side where the form is
  // negative (inside the circle for A > 0) is away from the obstacle, i.e. ∇ points at it.
  const Eigen::Vector2d towards_obstacle = -detail::project(model.scene.obstacles[contact.obstacle], mean).normal;
  const double sign = Eigen::Vector2d(D, E).dot(towards_obstacle) >= 0 ? 1.0 : -1.0;
  return sign * 2 * A / gradient / scale;
}

// 1/R = body curvature + obstacle curvature, and the words for where it came from.
std::optional<std::pair<double, std::string>> relative_curvature(const Model& model, const ObstacleContact& contact) {
  const Scene& scene = model.scene;
  const ObstacleSpec& obstacle = scene.obstacles[contact.obstacle];
  if (obstacle.type == "profile") return std::nullopt;
  const double obstacle_curvature = detail::obstacle_curvature(obstacle);
  double body_curvature = 0;
  std::string source;
  if (scene.body.shape == "half_disc" && scene.contact.boundary == "arc") {
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
  if (!(curvature > 0) || curvature * std::max(contact.half_width, 1e-300) < 1e-6) return std::nullopt;
  return std::make_pair(curvature, source);
}

}  // namespace

std::optional<HertzComparison> compare_with_hertz(const Model& model, const ContactSummary& contact) {
  if (contact.obstacles.size() != 1) return std::nullopt;
  return compare_with_hertz(model, contact.obstacles[0]);
}

std::optional<HertzComparison> compare_with_hertz(const Model& model, const ObstacleContact& contact) {
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
