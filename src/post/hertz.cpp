// Hertz's cylinder on a rigid plane (plane strain or plane stress), ARCHITECTURE.md:
//   b = sqrt(4 P R / (π E*)),  p0 = 2P / (π b),  p(x) = p0 sqrt(1 − x²/b²).
#include <algorithm>
#include <cmath>

#include "contactqp/post.hpp"

namespace contactqp {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Gauss–Legendre, 8 points on [−1, 1].
const double kNodes[] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                         0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
const double kWeights[] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                           0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

// The computed pressure between profile points, linear in s; zero beyond the candidates.
double interpolated_pressure(const std::vector<ContactProfilePoint>& profile, double s) {
  if (profile.empty() || s < profile.front().s || s > profile.back().s) return 0.0;
  auto upper = std::lower_bound(profile.begin(), profile.end(), s,
                                [](const ContactProfilePoint& p, double value) { return p.s < value; });
  if (upper == profile.begin()) return upper->pressure;
  const auto lower = upper - 1;
  const double t = (s - lower->s) / (upper->s - lower->s);
  return (1 - t) * lower->pressure + t * upper->pressure;
}

}  // namespace

double hertz_pressure(const HertzComparison& hertz, double x) {
  const double b = hertz.half_width;
  if (!(b > 0) || std::abs(x) >= b) return 0.0;
  return hertz.max_pressure * std::sqrt(1.0 - (x / b) * (x / b));
}

std::optional<HertzComparison> compare_with_hertz(const Model& model, const ContactSummary& contact) {
  const Scene& scene = model.scene;
  if (scene.body.shape != "half_disc" || scene.obstacles.size() != 1 || scene.obstacles[0].type != "plane")
    return std::nullopt;
  if (!(contact.line_load > 0)) return std::nullopt;

  HertzComparison hertz;
  const double E = scene.material.E, nu = scene.material.nu, R = scene.body.radius;
  const double P = contact.line_load;
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
