// The half-disc body of Hertz's problem, meshed by Gmsh with triangles graded from a fine
// size along the candidate contact arc to a coarse size far from it.
#pragma once

#include "contactqp/mesh.hpp"
#include "graded_size.hpp"
#include "refine.hpp"

namespace contactqp::detail {

// The body is the lower half of the disc of radius R centred at (0, R). A point of its arc is
// P(φ) = (R sin φ, R − R cos φ), φ ∈ [−π/2, π/2] (or [0, π/2] with symmetry); φ = 0 is the
// lowest point.
struct HalfDiscMeshRequest {
  double radius = 1;
  bool symmetry = false;
  double size = 0.1;           // far-field element size (length)
  double contact_size = 0.01;  // element size along the fine arc (length)
  double grading = 0.25;       // size growth per unit distance from the fine arc
  int order = 1;
  // Gmsh meshes sizes 2^refinements times larger (the grading too, so the refined size is the
  // same function of the distance) and each triangle is split into four that many times, its
  // new arc nodes put back on the circle: Gmsh's time grows faster than its triangles.
  int refinements = 0;
  Intervals fine;  // the fine arcs, as angles φ; a single point when nothing can touch
  // When set, the element size wanted at each point (graded_size.hpp), in place of size,
  // contact_size and grading; refinements must then be 0.
  SizeField size_field;
};

// Boundaries of the result: "arc", "top", and "symmetry" (x = 0) when symmetric.
Mesh mesh_half_disc(const HalfDiscMeshRequest& request);

// What Gmsh meshes for it, and how that is refined (refine.hpp): mesh_half_disc() is
// refine_coarse() of it.
CoarseMesh coarse_half_disc(const HalfDiscMeshRequest& request);
// Its snap, in units of R: new nodes of "arc" back onto the unit circle about (0, 1).
SnapToBoundary half_disc_snap();

// The number of triangles the request will give, within a factor of about 1.5, computed
// without meshing (so that an oversized request can be refused before it takes the memory).
double estimate_half_disc_triangles(const HalfDiscMeshRequest& request);

}  // namespace contactqp::detail
