// The size field of the generated shapes: contact_size on the curves where contact can
// happen, growing by `grading` per unit distance from them up to `size`, and the number of
// triangles that gives (so an oversized request is refused before it takes the memory).
#pragma once

#include <vector>

namespace contactqp::detail {

// Parts of a boundary curve's parameter range that are refined: sorted, disjoint intervals
// [from, to]; from == to for a single point.
using Intervals = std::vector<std::pair<double, double>>;

// The curve's breakpoints: start, end and every interval end within them, sorted, without
// near-duplicates (closer than 1e-9).
std::vector<double> breakpoints(double start, double end, const Intervals& fine, std::vector<double> extra = {});

// Whether t lies strictly inside one of the intervals; their total length.
bool inside(const Intervals& fine, double t);
double total_length(const Intervals& fine);

struct GradedSize {
  double size = 0.1;           // far-field element size
  double contact_size = 0.01;  // element size on the fine curves
  double grading = 0.1;        // size growth per unit distance from them
};

// Sets Gmsh's background mesh to the graded size around `fine_curves` (of total length
// `fine_length`), or around the geometry point `fallback_point` when there is no fine curve.
// Call between geo::synchronize() and mesh::generate().
void set_graded_size_field(const GradedSize& sizes, const std::vector<int>& fine_curves, double fine_length,
                           int fallback_point);

// Triangles of a body of area `area` meshed with that field around fine curves of length
// `fine_length`, within a factor of about 1.5. All lengths in one unit.
double estimate_graded_triangles(const GradedSize& sizes, double area, double fine_length);

}  // namespace contactqp::detail
