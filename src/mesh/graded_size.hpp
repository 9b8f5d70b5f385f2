// The size field of the generated shapes: contact_size on the curves (2D) or the zone (3D)
// where contact can happen, growing by `grading` per unit distance from them up to `size`, and
// the number of triangles or tetrahedra that gives (so an oversized request is refused before
// it takes the memory).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
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

// length / unit rounded to 12 significant digits: the 3D shapes are meshed in units of one of
// their lengths, and a scene scaled by any factor must give exactly the scaled mesh. Without
// the rounding it did not: R = 0.7 and size = 0.2·0.7 give 0.19999999999999998 in units of R,
// and Gmsh's 3D Delaunay meshes that differently from 0.2 (15 634 against 15 617 tetrahedra).
double unit_length(double length, double unit);

// Gmsh's tetrahedral meshers, by name (its Mesh.Algorithm3D 1 and 10).
enum class VolumeAlgorithm {
  Delaunay,  // the default: the same mesh on every run
  Hxt,       // 1.4–5.6 times less CPU on the quarter hemisphere (contact sizes 0.02–0.005 R,
             // orders 1–2), but not reproducible: its mesh differs from run to run in Gmsh
             // 4.8, even on one thread
};

// 3D: sets Gmsh's background mesh to s(x) = min(size, contact_size + grading · d(x)), where
// `distance` is d(x) as a Gmsh MathEval expression in x, y, z (the distance from the fine
// zone, 0 inside it), and the options of the 3D meshers: sizes from the field only, surfaces
// by Frontal-Delaunay, volumes by `algorithm`. Call between occ::synchronize() and
// mesh::generate(3).
void set_graded_size_expression(const GradedSize& sizes, const std::string& distance, VolumeAlgorithm algorithm);

// A wanted element size at each point, in the body's own frame and lengths (MeshSpec::size_field).
using SizeField = std::function<double(const Eigen::Vector3d& x)>;

// Sets Gmsh's mesh size to `field` instead of a graded field (call where set_graded_size_field
// or set_graded_size_expression would be): Gmsh, meshing in units of `unit`, asks for the size
// at each point through its size callback (GmshSession removes it). The meshers' options are
// those of the graded fields (sizes from the field only, Frontal-Delaunay surfaces, volumes by
// `algorithm`).
void set_size_field(const SizeField& field, double unit, VolumeAlgorithm algorithm = VolumeAlgorithm::Delaunay);

// Tetrahedra of a body of volume `volume` meshed with the graded size of the distance d from
// its fine zone, within a factor of about 2: the zone (d = 0) holds `fine_volume`, and
// shell_area(d) is the area of the body's points at distance d > 0 (the derivative of the
// volume within distance d). Shells are counted until they cover the body's volume, the rest
// at the far-field size. All lengths in one unit.
double estimate_graded_tetrahedra(const GradedSize& sizes, double volume, double fine_volume,
                                  const std::function<double(double)>& shell_area);

}  // namespace contactqp::detail
