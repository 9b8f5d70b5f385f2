// The peer's mesh read back by contactqp: the explicit check that GetFEM and contactqp solve on
// the same mesh (benchmarks/peers/getfem_hertz.py writes it with --msh).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "contactqp/mesh.hpp"

namespace contactqp::bench {

struct PeerMeshCheck {
  std::string file;                                         // the .msh read
  int nodes = 0, triangles = 0, dofs = 0, constraints = 0;  // of the model built on it
  // The largest distance from a node of `mesh` to the nearest node of the file's mesh (length);
  // 0 when both have the same nodes. +inf when a node has no partner within 1e-9 of the size.
  double max_node_distance = 0;
};

// Builds the model of `scene` (a half-disc scene's JSON) with its body replaced by the Gmsh
// file `msh` (physical curves "arc", "top", "symmetry"), and compares it with `mesh`, the mesh
// contactqp generated for the same scene. Throws InputError when the file cannot be used.
PeerMeshCheck check_peer_mesh(const nlohmann::json& scene, const std::string& msh, const Mesh& mesh);

}  // namespace contactqp::bench
