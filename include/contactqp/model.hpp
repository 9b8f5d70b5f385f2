// The model: a scene turned into a mesh with boundary conditions and contact candidates, and
// the assembly of its quadratic program.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "contactqp/mesh.hpp"
#include "contactqp/qp.hpp"
#include "contactqp/scene.hpp"

namespace contactqp {

struct BuildOptions {
  long long max_elements = 4'000'000;  // refuse scenes whose mesh would exceed this many triangles
};

// A contact candidate: one node of the contact boundary that may touch one obstacle.
struct Candidate {
  int node = -1;
  int obstacle = -1;
  double gap = 0;              // initial gap (x_i − p)·n along the obstacle normal (length)
  double tributary = 0;        // boundary length the node stands for: ∫ N_i ds over its edges (length)
};

struct Model {
  Scene scene;
  Mesh mesh;
  // DOF d = 2·node + component. free_index[d] is its column in K, or −1 when prescribed.
  std::vector<int> free_index;
  Eigen::VectorXd prescribed;  // 2·n_nodes: the prescribed displacement of each prescribed DOF, 0 elsewhere
  int n_free = 0;
  std::vector<Candidate> candidates;  // one constraint row each, in row order
  double max_gap = 0;                 // the candidate distance used (length); +inf when every facing node
  std::string max_gap_rule;           // how max_gap was chosen, for the report
  std::vector<std::string> warnings;  // e.g. near-incompressible linear triangles
  Timings timings;                    // "mesh", "model"
};

// Builds mesh, boundary conditions and candidates. Throws InputError on a scene that cannot
// be modelled (element limit, a boundary condition that penetrates an obstacle, ...).
Model build_model(const Scene& scene, const BuildOptions& options = {});

// Assembles K (free DOFs), f (prescribed displacements moved to the right-hand side), and
// one row of B and g per candidate. Records "assemble" in model timings.
QuadraticProgram assemble_qp(Model& model);

// The full nodal displacement field (2·n_nodes) from the free DOFs u.
Eigen::VectorXd full_displacement(const Model& model, const Eigen::VectorXd& u);

// Elasticity matrix D (stress = D · [εxx, εyy, 2εxy]) of the scene's plane model.
Eigen::Matrix3d elasticity_matrix(PlaneModel model, const Material& material);

// Stiffness of one triangle (2·nodes_per_element square, DOFs [u0x, u0y, u1x, ...]), per
// `thickness`. Isoparametric: quadratic triangles may have curved sides.
Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const Eigen::Matrix3d& D,
                                  double thickness);

}  // namespace contactqp
