// Volumes and boundaries of a 3D mesh, for the mesher and refinement tests.
#pragma once

#include <Eigen/Dense>  // determinant()
#include <catch2/catch.hpp>
#include <set>

#include "contactqp/mesh.hpp"
#include "mesh/shape_functions.hpp"

namespace contactqp::testing {

// The sum of the straight elements' volumes (element_measure).
inline double total_volume(const Mesh& mesh) {
  double volume = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) volume += element_measure(mesh, e);
  return volume;
}

// The volume of a curved 10-node mesh: det J of its isoparametric map integrated by the
// 4-point rule. det J of a curved element is a polynomial of degree 3, so the rule is not
// exact, but its error is far below the tolerances tested (only the surface layer is curved).
inline double isoparametric_volume(const Mesh& mesh) {
  const detail::TetrahedronPoint* points;
  const int n = detail::tetrahedron_rule(2, points);
  double volume = 0;
  for (int e = 0; e < mesh.n_elements(); ++e) {
    const int* v = mesh.element(e);
    for (int q = 0; q < n; ++q) {
      const auto dN = detail::tetrahedron_gradients(2, points[q].xi, points[q].eta, points[q].zeta);
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 10; ++i) J += dN.col(i) * mesh.nodes[v[i]].transpose();
      volume += points[q].weight * J.determinant();
    }
  }
  return volume;
}

// Every face of the body's outer boundary belongs to exactly one named boundary, and every
// named face is an outer face (so the boundaries tile the surface).
inline void check_boundaries_tile_surface(const Mesh& mesh) {
  std::multiset<std::set<int>> outer, named;
  for (const BoundaryFace& face : outer_boundary(mesh)) outer.insert({face.nodes[0], face.nodes[1], face.nodes[2]});
  for (const auto& [name, faces] : mesh.boundaries)
    for (const BoundaryFace& face : faces) named.insert({face.nodes[0], face.nodes[1], face.nodes[2]});
  CHECK(named.size() == outer.size());
  CHECK(named == outer);
}

}  // namespace contactqp::testing
