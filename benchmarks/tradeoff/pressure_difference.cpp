#include "pressure_difference.hpp"

#include <algorithm>
#include <cmath>

namespace contactqp::bench {
namespace {

// ∫ (p_a − p_b)² ds and ∫ p_b² ds, piece by piece between the breaks.
std::pair<double, double> integrals(const std::vector<ContactProfilePoint>& a,
                                    const std::vector<ContactProfilePoint>& b) {
  std::vector<double> breaks;
  for (const auto* profile : {&a, &b})
    for (const ContactProfilePoint& point : *profile) breaks.push_back(point.s);
  std::sort(breaks.begin(), breaks.end());
  const double gauss = 1.0 / std::sqrt(3.0);
  double difference = 0, norm = 0;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double lo = breaks[k], hi = breaks[k + 1];
    if (!(hi > lo)) continue;
    for (const double x : {-gauss, gauss}) {
      const double s = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
      const double pa = interpolated_pressure(a, s), pb = interpolated_pressure(b, s);
      difference += 0.5 * (hi - lo) * (pa - pb) * (pa - pb);
      norm += 0.5 * (hi - lo) * pb * pb;
    }
  }
  return {difference, norm};
}

}  // namespace

double relative_l2_difference(const std::vector<ContactProfilePoint>& a, const std::vector<ContactProfilePoint>& b) {
  const auto [difference, norm] = integrals(a, b);
  return norm > 0 ? std::sqrt(difference / norm) : 0.0;
}

}  // namespace contactqp::bench
