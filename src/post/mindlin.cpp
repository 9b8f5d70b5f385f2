// Cattaneo–Mindlin's partial slip (docs/friction.md): after Hertz's normal force P, a tangential
// force Q < μP leaves a stick zone of half-width c = b sqrt(1 − Q/(μP)) (two cylinders) or radius
// c = a (1 − Q/(μP))^(1/3) (two spheres) inside a slip annulus where q = μp. The theory neglects
// the coupling of normal and tangential tractions, which vanishes for Dundurs' β = 0.
#include <algorithm>
#include <cmath>

#include "contactqp/post.hpp"
#include "qp/pi.hpp"

namespace contactqp {
namespace {

constexpr double kNoShear = 0.01;  // Q/(μP) below this: a press step, q measured against μp

double shear_modulus(const Material& m) { return m.E / (2 * (1 + m.nu)); }

// Dundurs' β of body 1 against body 2 (plane strain); a rigid body 2 gives −(1 − 2ν1)/(2(1 − ν1)).
double dundurs_beta(const Material& body, const Material* other) {
  const double G1 = shear_modulus(body), nu1 = body.nu;
  if (!other) return -(1 - 2 * nu1) / (2 * (1 - nu1));
  const double G2 = shear_modulus(*other), nu2 = other->nu;
  return (G1 * (1 - 2 * nu2) - G2 * (1 - 2 * nu1)) / (2 * G1 * (1 - nu2) + 2 * G2 * (1 - nu1));
}

}  // namespace

double mindlin_traction(const MindlinComparison& mindlin, double x) {
  const double b = mindlin.half_width, c = mindlin.stick_size, x2 = x * x;
  if (!(b > 0) || x2 >= b * b) return 0.0;
  const double limit = mindlin.coefficient * mindlin.max_pressure;
  double q = limit * std::sqrt(1 - x2 / (b * b));
  if (x2 < c * c) q -= limit * (c / b) * std::sqrt(1 - x2 / (c * c));
  return q;
}

MindlinComparison compare_with_mindlin(const Model& model, const FrictionFields& fields,
                                       const std::vector<ContactProfilePoint>& profile, double centre,
                                       const HertzComparison& hertz, double coefficient, const FrictionZone& zone,
                                       const Material& body, const Material* other) {
  MindlinComparison m;
  const int dim = model.dim;
  const double thickness = dim == 2 ? model.scene.body.thickness : 1.0;
  m.dim = dim;
  m.coefficient = coefficient;
  m.normal_force = hertz.force;
  m.tangential_force = zone.tangential_force / thickness;
  m.load_ratio = m.tangential_force / (coefficient * m.normal_force);
  m.dundurs_beta = dundurs_beta(body, other);
  m.half_width = dim == 2 ? hertz.half_width : hertz.contact_radius;
  m.max_pressure = hertz.max_pressure;
  const double b = m.half_width, slipping = std::min(1.0, m.load_ratio);
  m.stick_size = dim == 2 ? b * std::sqrt(1 - slipping) : b * std::cbrt(1 - slipping);
  m.stick_size_computed = zone.stick_size;
  m.error_stick_size = (m.stick_size_computed - m.stick_size) / (m.stick_size > 0 ? m.stick_size : b);

  // The traction along Q against Mindlin's: L2 over the zone, by the trapezoidal rule along s
  // in 2D and by the rows' tributary areas in 3D (as Hertz's pressure error).
  const Eigen::Vector3d along =
      zone.tangential_force > 0 ? Eigen::Vector3d(zone.resultant / zone.tangential_force) : Eigen::Vector3d::Zero();
  auto difference = [&](const ContactProfilePoint& p, double limit) {
    const double x = dim == 2 ? p.s - centre : p.s;
    const double q = fields.traction[p.row].dot(along), reference = mindlin_traction(m, x);
    return std::pair<double, double>{
        (q - reference) * (q - reference),
        limit > 0 ? limit * limit * (1 - std::min(1.0, x * x / (b * b))) : reference * reference};
  };
  auto l2 = [&](double limit) {  // limit > 0: the reference is μ p instead of q
    double error = 0, reference = 0;
    if (dim == 2) {
      for (size_t k = 0; k + 1 < profile.size(); ++k) {
        const double h = profile[k + 1].s - profile[k].s;
        const auto [e0, r0] = difference(profile[k], limit);
        const auto [e1, r1] = difference(profile[k + 1], limit);
        error += 0.5 * h * (e0 + e1);
        reference += 0.5 * h * (r0 + r1);
      }
    } else {
      for (const ContactProfilePoint& p : profile) {
        const auto [e, r] = difference(p, limit);
        error += model.candidates[p.row].tributary * e;
        reference += model.candidates[p.row].tributary * r;
      }
    }
    return std::pair<double, double>{error, reference};
  };
  auto [error, reference] = l2(0.0);
  // No tangential force to speak of (a press step: Q is the solver's round-off, 1e-4 μP or
  // less): Mindlin's q nearly vanishes and an error relative to it means nothing (it read 1601
  // on scenes/mindlin-spheres.json's press); measure against the slip limit μp instead.
  if (!(m.load_ratio >= kNoShear) || !(reference > 0)) std::tie(error, reference) = l2(coefficient * m.max_pressure);
  m.error_l2 = reference > 0 ? std::sqrt(error / reference) : 0.0;

  const double P = m.normal_force, Q = m.tangential_force, mu = coefficient;
  if (dim == 3) {
    const double C = (2 - body.nu) / shear_modulus(body) + (other ? (2 - other->nu) / shear_modulus(*other) : 0.0);
    m.slip_displacement = 3 * mu * P * C / (16 * b) * (1 - std::pow(1 - slipping, 2.0 / 3.0)) - Q * C / (8 * b);
  } else {
    const double ratio = m.stick_size / b;  // c/b
    const double log_term = ratio > 0 ? ratio * ratio * std::log(1 / ratio) : 0.0;
    m.slip_displacement = 2 / (kPi * hertz.effective_modulus) * (std::min(Q, mu * P) / 2 - mu * P * log_term);
  }
  return m;
}

}  // namespace contactqp
