// The hemisphere body of Hertz's problem in 3D, meshed by Gmsh with tetrahedra graded from a
// fine size around the lowest point (where contact starts) to a coarse size far from it.
#pragma once

#include "contactqp/mesh.hpp"
#include "graded_size.hpp"
#include "refine.hpp"

namespace contactqp::detail {

// The body is the lower half of the ball of radius R centred at (0, 0, R): its flat top is the
// disc z = R, its lowest point (0, 0, 0). With symmetry, the quarter x ≥ 0, y ≥ 0 of it (or
// the half beside one cut).
//
// The fine zone is the ball of radius fine_radius around the lowest point: the element size
// is contact_size within it and grows by `grading` per unit distance from it up to `size`,
// s(x) = min(size, contact_size + grading · max(0, |x| − fine_radius)). A contact zone given as
// a cap of polar angle φ around the lowest point (seen from the centre) is the fine radius
// 2R sin(φ/2), the chord from the lowest point to the cap's rim.
struct HemisphereMeshRequest {
  double radius = 1;
  bool symmetry = false;
  // With symmetry, the cuts: both (the quarter) or one (the half x ≥ 0 or y ≥ 0).
  bool symmetry_x = true, symmetry_y = true;
  double size = 0.1;           // far-field element size (length)
  double contact_size = 0.01;  // element size in the fine zone (length)
  double grading = 0.25;       // size growth per unit distance from the fine zone
  int order = 1;               // 1: 4-node tetrahedra; 2: 10-node (curved, mid-edge nodes on the sphere)
  double fine_radius = 0.1;    // length; 0 refines at the lowest point only
  // Gmsh meshes sizes and grading 2^refinements times larger (4-node tetrahedra) and each
  // tetrahedron is split into eight that many times, the new nodes of "surface" put back on
  // the sphere, then mid-edge nodes added for order 2 (half_disc_mesher.hpp: Gmsh's 3D
  // Delaunay takes most of a large run's mesh time). fine_radius is kept as it is.
  int refinements = 0;
  VolumeAlgorithm volume_algorithm = VolumeAlgorithm::Delaunay;  // see graded_size.hpp
  // When set, the element size wanted at each point (graded_size.hpp), in place of size,
  // contact_size and grading; refinements must then be 0.
  SizeField size_field;
};

// A dim-3 Mesh with boundaries "surface" (the spherical part) and "top" (z = R), and with
// symmetry "symmetry_x" (the plane x = 0) and "symmetry_y" (y = 0). No regions or points.
// Every node of "surface", mid-edge nodes too, lies on the sphere. Throws std::runtime_error
// when Gmsh fails.
Mesh mesh_hemisphere(const HemisphereMeshRequest& request);

// What Gmsh meshes for it, and how that is refined (refine.hpp): mesh_hemisphere() is
// refine_coarse() of it.
CoarseMesh coarse_hemisphere(const HemisphereMeshRequest& request);
// Its snap, in units of R: new nodes of "surface" back onto the unit sphere about (0, 0, 1).
SnapToBoundary hemisphere_snap();

// The number of tetrahedra the request will give (refined ones too), within a factor of about 2, computed
// without meshing (so that an oversized request can be refused before it takes the memory).
double estimate_hemisphere_elements(const HemisphereMeshRequest& request);

}  // namespace contactqp::detail
