#include "graded_size.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "qp/pi.hpp"

namespace contactqp::detail {
namespace {

// Area of an equilateral triangle of side h is kTriangleArea · h².
constexpr double kTriangleArea = 0.4330127018922193;
// Volume of a regular tetrahedron of edge h is kTetrahedronVolume · h³ (h³ / (6√2)).
constexpr double kTetrahedronVolume = 0.11785113019775793;
// Gmsh's tetrahedra are fewer than the volume over that of a regular tetrahedron of edge s(x):
// 0.54–0.62 of it (Delaunay) and 0.46–0.53 (HXT) on the quarter hemisphere, 0.59–0.73 on the
// box, over contact sizes 0.005–0.2 and gradings 0.1–0.3 (its edges come out longer than the
// size asked for). The estimate is scaled by the middle of that range.
constexpr double kGmshTetrahedra = 0.6;

}  // namespace

std::vector<double> breakpoints(double start, double end, const Intervals& fine, std::vector<double> extra) {
  extra.push_back(start);
  extra.push_back(end);
  for (const auto& [from, to] : fine) {
    extra.push_back(std::clamp(from, start, end));
    extra.push_back(std::clamp(to, start, end));
  }
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }),
              extra.end());
  return extra;
}

bool inside(const Intervals& fine, double t) {
  for (const auto& [from, to] : fine)
    if (t > from && t < to) return true;
  return false;
}

double total_length(const Intervals& fine) {
  double length = 0;
  for (const auto& [from, to] : fine) length += std::max(0.0, to - from);
  return length;
}

void set_graded_size_field(const GradedSize& sizes, const std::vector<int>& fine_curves, double fine_length,
                           int fallback_point) {
  namespace field = gmsh::model::mesh::field;
  const int distance = field::add("Distance");
  if (!fine_curves.empty()) {
    std::vector<double> curve_list(fine_curves.begin(), fine_curves.end());
    field::setNumbers(distance, "CurvesList", curve_list);
    field::setNumber(distance, "NumPointsPerCurve",
                     std::max(20.0, 4.0 * fine_length / sizes.contact_size / fine_curves.size()));
  } else {
    // No curve can touch: refine at the point closest to the obstacle all the same.
    field::setNumbers(distance, "PointsList", {static_cast<double>(fallback_point)});
  }
  const int size_field = field::add("MathEval");
  char expression[256];
  std::snprintf(expression, sizeof expression, "Min(%.17g, %.17g + %.17g * F%d)", sizes.size, sizes.contact_size,
                sizes.grading, distance);
  field::setString(size_field, "F", expression);
  field::setAsBackgroundMesh(size_field);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped triangles
}

double estimate_graded_triangles(const GradedSize& sizes, double area, double fine_length) {
  // The size grows linearly with the distance d from the fine curves, s(d) = cs + γ d; the band
  // of the body at distance in [d, d + dd] has area about (ℓ + π d) dd, capped by the body's
  // area. Each band's triangles, ∫ (ℓ + π d) / (k s²) dd, are integrated exactly: a midpoint
  // rule misses almost all of them when cs is far below the band width (contact_size 1e-9
  // was estimated at 1e5 triangles and took all the memory), and a size that underflows to 0
  // gives +inf, never 0/0.
  const double cs = sizes.contact_size, h = sizes.size, gamma = sizes.grading, l = fine_length;
  double covered = 0, triangles = 0;
  const double d_max = std::max(0.0, (h - cs) / gamma);
  const int steps = 400;
  for (int k = 0; k < steps && covered < area; ++k) {
    const double d0 = d_max * k / steps, d1 = d_max * (k + 1) / steps;
    const double s0 = cs + gamma * d0, s1 = cs + gamma * d1;
    const double band = l * (d1 - d0) + 0.5 * kPi * (d1 * d1 - d0 * d0);
    if (!(band > 0)) continue;
    // With d = (s − cs)/γ: (1/γ) [(ℓ − π cs/γ)(1/s0 − 1/s1) + (π/γ) ln(s1/s0)].
    const double in_band = ((l - kPi * cs / gamma) * (1 / s0 - 1 / s1) + kPi / gamma * std::log(s1 / s0)) / gamma;
    const double fraction = std::min(1.0, (area - covered) / band);
    triangles += fraction * in_band / kTriangleArea;
    covered += fraction * band;
  }
  triangles += std::max(0.0, area - covered) / (kTriangleArea * h * h);
  return triangles;
}

double unit_length(double length, double unit) {
  char text[32];
  std::snprintf(text, sizeof text, "%.12g", length / unit);
  return std::strtod(text, nullptr);
}

void set_graded_size_expression(const GradedSize& sizes, const std::string& distance, VolumeAlgorithm algorithm) {
  // The distance is written out in x, y, z rather than taken from a Distance field: in 3D that
  // field measures to sampled points of curves or to the nodes of already meshed surfaces,
  // while the fine zones of the generated shapes (a ball, a disc) have closed-form distances.
  namespace field = gmsh::model::mesh::field;
  const int size_field = field::add("MathEval");
  char expression[512];
  std::snprintf(expression, sizeof expression, "Min((%.17g), (%.17g) + (%.17g) * (%s))", sizes.size, sizes.contact_size,
                sizes.grading, distance.c_str());
  field::setString(size_field, "F", expression);
  field::setAsBackgroundMesh(size_field);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped surface triangles
  gmsh::option::setNumber("Mesh.Algorithm3D", algorithm == VolumeAlgorithm::Hxt ? 10 : 1);
}

void set_size_field(const SizeField& field, double unit, VolumeAlgorithm algorithm) {
  // Gmsh 4.8 takes the smaller of the callback's size and the other sources': with no
  // background field and no size from points or curvature, the callback's.
  gmsh::model::mesh::setSizeCallback(
      [field, unit](int, int, double x, double y, double z) { return field(Eigen::Vector3d(x, y, z) * unit) / unit; });
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.Algorithm", 6);
  gmsh::option::setNumber("Mesh.Algorithm3D", algorithm == VolumeAlgorithm::Hxt ? 10 : 1);
}

double estimate_graded_tetrahedra(const GradedSize& sizes, double volume, double fine_volume,
                                  const std::function<double(double)>& shell_area) {
  // As in 2D, the size s(d) = cs + γ d is integrated exactly in its own variable: with
  // t = ln s, dd = s dt / γ, a shell holds A(d) s dt / γ of volume and A(d) dt / (γ k s²)
  // tetrahedra, smooth in t however small cs is against the body.
  const double cs = sizes.contact_size, h = sizes.size, gamma = sizes.grading;
  if (!(gamma > 0) || !(h > cs)) {  // one size everywhere
    const double s = std::min(cs, h);
    return kGmshTetrahedra * volume / (kTetrahedronVolume * s * s * s);
  }
  double covered = std::min(volume, fine_volume);
  double tetrahedra = covered / (kTetrahedronVolume * cs * cs * cs);
  const int steps = 2000;
  const double t0 = std::log(cs), dt = (std::log(h) - t0) / steps;
  for (int k = 0; k < steps && covered < volume; ++k) {
    const double s = std::exp(t0 + (k + 0.5) * dt);
    const double area = shell_area((s - cs) / gamma);
    const double shell = area * s * dt / gamma;
    if (!(shell > 0)) continue;
    const double fraction = std::min(1.0, (volume - covered) / shell);
    tetrahedra += fraction * area * dt / (gamma * kTetrahedronVolume * s * s);
    covered += fraction * shell;
  }
  tetrahedra += std::max(0.0, volume - covered) / (kTetrahedronVolume * h * h * h);
  return kGmshTetrahedra * tetrahedra;
}

}  // namespace contactqp::detail
