// The model: a scene turned into a mesh with boundary conditions and contact candidates, and
// the assembly of its quadratic program.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "contactqp/mesh.hpp"
#include "contactqp/qp.hpp"
#include "contactqp/scene.hpp"

namespace contactqp {

struct BuildOptions {
  long long max_elements =
      4'000'000;  // refuse scenes whose mesh would exceed this many elements (triangles or tetrahedra)
};

// A contact candidate: one node of the contact boundary that may touch one obstacle.
struct Candidate {
  int node = -1;
  int obstacle = -1;
  double gap = 0;  // initial gap (x_i − p)·n along the obstacle normal (length)
  // The boundary the node stands for, ∫ N_i over its faces: in 2D a length (∫ N_i ds over its
  // edges), in 3D an area (a third of each linear face; for a 6-node face 0 at its vertices
  // and a third of the face at each mid-side node: docs/scenes.md, "Tributary areas").
  double tributary = 0;
  // Between two bodies (docs/bodies.md): the row −nᵀ(u_i − Σ_j N_j(ξ) u_j) ≤ g of the node
  // against the closest point ξ on the other body's boundary face. obstacle is then −1.
  int pair = -1;        // index into scene.pairs, or −1 for an obstacle's row
  int body = 0;         // the body the node belongs to
  int other_body = -1;  // the body of the face (pairs)
  int face = -1;        // the face's index in its boundary (pairs)
  // The other side's nodes in the row and their weights, summing to 1: N_j(ξ) of one face
  // (node-to-face rows), or the mortar weights M_ij / D_i over the faces the node's share of its
  // side overlaps (ContactPair::rows, docs/bodies.md).
  int n_face_nodes = 0;
  std::vector<int> face_nodes;
  std::vector<double> weights;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // the face's outward unit normal at ξ (global axes)
  // Pairs: the common normal at ξ, (n_face − n_node)/|…| from the two sides' smoothed normals,
  // the line along which the node met its partner: the frame of the friction rows, whose
  // tangents must not see the gap close (on curved sides n leans off it); zero for obstacles.
  Eigen::Vector3d common_normal = Eigen::Vector3d::Zero();
};

// One body of a scene with several, within the model's one mesh: its nodes and elements are
// consecutive, so its DOFs are a block of K's and K is block-diagonal over the bodies.
struct ModelBody {
  std::string name;
  Scene scene;  // the body as a one-body scene: its material, shape, own loads, the obstacles
  BodyPlacement placement;
  int first_node = 0, n_nodes = 0, first_element = 0, n_elements = 0;
};

// Which side of a contact pair carries the nodes (the other the faces), and why.
struct PairSides {
  int node_side = 0;                              // 0 or 1: the index into ContactPair::body
  std::string rule;                               // e.g. "finer mesh"
  double node_face_size = 0, face_face_size = 0;  // the smallest face of each side's boundary (length)
};

// One load's own share of the model, for load steps (scene.steps): apply_load_step() scales it.
struct LoadShare {
  Eigen::VectorXd nodal_force;                     // dim·n_nodes, global axes: the load's consistent nodal forces
  std::vector<std::pair<int, double>> prescribed;  // (DOF, value) the load prescribes, as Model::prescribed holds it
};

// One rigid motion of a body that nothing prescribed holds, in the scene's own frame
// (docs/extremes.md, "Bodies held only by their contacts").
struct FreeMotion {
  Eigen::VectorXd rigid;  // (t_x, t_y, r) in 2D, (t, ω) in 3D: t + ω × (x − centre)/extent
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the rotations' centre: the part's centroid
  double extent = 1;                                 // the rotations' scale: the part's size
  int part = 0;                                      // the connected part of the mesh it moves
  int first_node = 0;                                // a node of that part (its body: Model::body_of_node)
};

// A boundary that a force load (RigidForceLoad) moves as one rigid surface along one component:
// its nodes' DOFs of that component share one column of K (free_index maps them all to it),
// so K, B and f there are the sums over the surface (TᵀKT, BT, Tᵀf for the tie u = T u').
struct RigidSurface {
  int load = -1;           // its entry in scene.loads
  int component = 0;       // along the DOF frame's column (the scene's own axis)
  int column = -1;         // the shared free DOF
  double force = 0;        // the whole body's resultant along it, at the current load step
  std::vector<int> nodes;  // ascending
};

// A force load's rigid surface that also turns (RigidForceLoad::moment): one column of K per axis
// it turns about. Its tied DOFs move by the surface's translation plus the turn, u_i = t + θ ×
// (x_i − centre) (the lever arms: Model::levers), so t is the translation at `centre`.
struct RigidRotation {
  int load = -1;                                     // its entry in scene.loads
  int axis = 2;                                      // about the scene's own axis (z in 2D)
  int column = -1;                                   // the angle's free DOF
  double moment = 0;                                 // the whole body's moment about it, at the current load step
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the point it turns about, global frame
  std::vector<int> nodes;                            // ascending, the surface's
};

// The share of a turning surface's angle in one tied DOF: DOF `dof` moves by weight × u[column]
// beyond u[free_index[dof]] (for_each_column()).
struct Lever {
  int dof = 0;
  int column = 0;
  double weight = 0;
};

struct Model {
  // The scene as solved, in the global frame: its transform is applied (obstacles and load
  // vectors rotated) and reset; `rotation` remembers it (a rotation about z in 2D).
  Scene scene;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Mesh mesh;    // in the global frame
  int dim = 2;  // mesh.dim, the scene's dimension
  // DOF d = dim·node + component. free_index[d] is its column in K, or −1 when prescribed.
  // A node's components are along the columns of its DOF frame (dof_frame(): the global axes,
  // except at nodes with a prescribed displacement in a rotated scene, whose components stay
  // along the scene's own axes so that "[null, −δ]" keeps its meaning).
  std::vector<int> free_index;
  Eigen::VectorXd prescribed;           // dim·n_nodes: the prescribed displacement of each prescribed DOF, 0 elsewhere
  std::vector<int> frame_of_node;       // n_nodes: index into `frames`, −1 for the global axes; empty when all are
  std::vector<Eigen::MatrixXd> frames;  // dim × dim, orthogonal; column c is the direction of DOF component c
  // Force loads on rigid surfaces: one entry per load and tied component (ascending load, then
  // component). Several DOFs then map to one free index: it is injective only when this is empty.
  std::vector<RigidSurface> rigid_surfaces;
  // Surfaces that also turn: one entry per load and axis, their columns after every other one.
  // `levers` holds each tied DOF's share of their angles, sorted by DOF; both are empty without
  // a moment, and then free_index alone maps the DOFs to the columns.
  std::vector<RigidRotation> rigid_rotations;
  std::vector<Lever> levers;
  // dim·n_nodes, global axes: consistent nodal forces of the force loads (traction, pressure,
  // gravity, point), for the body's thickness in 2D (force).
  Eigen::VectorXd nodal_force;
  int n_free = 0;
  std::vector<Candidate> candidates;  // one constraint row each, in row order
  double max_gap = 0;                 // the candidate distance used (length); +inf when every facing node
  std::string max_gap_rule;           // how max_gap was chosen, for the report
  std::vector<std::string> warnings;  // e.g. near-incompressible linear triangles
  Timings timings;                    // "mesh", "model"
  // Several bodies (scene.bodies): each one's place in the mesh, the body of each element, the
  // pairs' sides. Empty for a one-body scene. Boundaries of the mesh are then "body.boundary".
  std::vector<ModelBody> bodies;
  std::vector<int> element_body;
  std::vector<PairSides> pair_sides;
  // With load steps (scene.steps): each load's share, one per entry of scene.loads (which with
  // bodies holds every body's loads, in order). Empty without steps. The model as built has
  // every load in full; apply_load_step() sets a step's.
  std::vector<LoadShare> load_shares;
  // A body that only its contacts hold: the rigid motions nothing prescribed stops, and the same
  // on the free DOFs (n_free × k, K's null space: assemble_qp puts it in qp.null_space). Empty
  // when the prescribed displacements hold the body. One-body scenes on one process.
  std::vector<FreeMotion> free_motions;
  Eigen::MatrixXd free_modes;

  int body_of_node(int node) const;  // 0 for a one-body model
};

// The body element e belongs to (0 for a one-body model); element_laws() below has each body's law.
inline int body_of_element(const Model& model, int e) { return model.element_body.empty() ? 0 : model.element_body[e]; }

// Calls add(column, weight) for each column DOF `dof` moves with: its own (weight 1) unless it
// is prescribed, and on a turning surface each angle's, weighted by its lever arm. The DOF's
// displacement is Σ weight · u[column] (plus its prescribed value); a row or column of K, B or f
// on that DOF goes to each of them, times the weight (TᵀKT, BT, Tᵀf for u = T u').
template <class Add>
void for_each_column(const Model& model, int dof, Add&& add) {
  const int column = model.free_index[static_cast<size_t>(dof)];
  if (column >= 0) add(column, 1.0);
  if (model.levers.empty()) return;
  auto at = std::lower_bound(model.levers.begin(), model.levers.end(), dof,
                             [](const Lever& lever, int d) { return lever.dof < d; });
  for (; at != model.levers.end() && at->dof == dof; ++at) add(at->column, at->weight);
}

// The turning surfaces' columns (translations and angles) that best fit `dof_values` (dim·n_nodes
// × k, each DOF along its frame's column) on their tied DOFs, written into those rows of
// `columns` (n_free × k): exact for a rigid motion, least squares for any other displacement.
// Nothing without a moment (model.rigid_rotations empty).
void fit_turning_surfaces(const Model& model, const Eigen::MatrixXd& dof_values, Eigen::MatrixXd& columns);

// Builds mesh, boundary conditions and candidates. Throws InputError on a scene that cannot
// be modelled (element limit, a boundary condition that penetrates an obstacle, ...).
Model build_model(const Scene& scene, const BuildOptions& options = {});

// Assembles K (free DOFs), f (prescribed displacements moved to the right-hand side, from
// every element) and one row of B and g per candidate. `elements` holds 1 for each element
// whose matrix K gets, or is empty for all of them: K is then a part of the problem's K, for
// a problem held in parts by several processes whose parts of the elements sum to the whole
// (include/contactqp/petsc/par_qp.hpp). Records "assemble" in model timings.
QuadraticProgram assemble_qp(Model& model, const std::vector<char>& elements = {});

// Sets the model and its QP to one load step: prescribed and nodal_force become the loads'
// shares scaled by `factors` (one per entry of model.scene.loads, load_factors()), and qp.f and
// qp.g follow; K, B and the friction rows are unchanged (the friction offset is the caller's:
// it depends on the last step's solution). InputError naming `step` when two loads then
// prescribe one DOF to different values. Needs model.load_shares (a scene with steps).
void apply_load_step(Model& model, QuadraticProgram& qp, const std::vector<double>& factors, const std::string& step);

// A motion d of the free DOFs (e.g. SolveResult::recession) as the body's free rigid motions
// that make it, in words in the scene's axes: "along +y", "by rotation about (0, 2), clockwise"; "" when
// the model has no free motion. With a verb each part's motion has its subject:
// "the body moves freely along +y", or in a scene with several bodies
// "body `ball` moves freely along +y".
std::string describe_free_motion(const Model& model, const Eigen::VectorXd& d, const std::string& verb = "");

// The full nodal displacement field (dim·n_nodes, global axes) from the free DOFs u.
Eigen::VectorXd full_displacement(const Model& model, const Eigen::VectorXd& u);

// The directions of a node's DOF components, as columns (dim × dim; the identity for the global axes).
Eigen::MatrixXd dof_frame(const Model& model, int node);

// Voigt size of the strain in dim dimensions: 3 ([εxx, εyy, 2εxy]) or 6 ([εxx, εyy, εzz, 2εyz, 2εxz, 2εxy]).
int voigt_size(int dim);

// Elasticity matrix D (stress = D · ε in Voigt form) of the model: 3 × 3 for the plane
// models, 6 × 6 for solid.
Eigen::MatrixXd elasticity_matrix(ElasticModel model, const Material& material);

// Stiffness of one triangle (2D convenience form: 2·nodes_per_element square, DOFs [u0x, u0y,
// u1x, ...]), per `thickness`. Isoparametric: quadratic triangles may have curved sides.
Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const Eigen::Matrix3d& D, double thickness);

// What an element's energy is, by body.formulation (docs/incompressible.md).
// Displacement: ½ ∫ εᵀ D ε. Mixed (plane strain): the elasticity matrix split as
// D = D_dev + k m mᵀ (m = [1, 1, 0], k = λ + 2μ/3 the bulk modulus, D_dev independent of λ),
// with the volumetric part seen only through the element mean of tr ε — an element-wise
// constant mean stress p = k·mean(tr ε) condensed out of the P2–P0 mixed form:
//   ½ ∫ εᵀ D_dev ε + ½ k |T| mean(tr ε)².
struct ElementLaw {
  Eigen::MatrixXd D = Eigen::Matrix3d::Zero();  // D (displacement) or D_dev (mixed), voigt_size(dim) square
  double bulk = 0;                              // k (mixed); 0 for the displacement formulation
  double shear = 0;                             // μ = E / (2(1 + ν))
  Formulation formulation = Formulation::Displacement;
  ElasticModel model = ElasticModel::PlaneStrain;
  double nu = 0;
};
ElementLaw element_law(ElasticModel model, const Material& material, Formulation formulation);
ElementLaw element_law(const Scene& scene);  // the scene's model, material and body.formulation
// One law per body (model.bodies order; one entry for a one-body model): index it by body_of_element().
std::vector<ElementLaw> element_laws(const Model& model);

// Stiffness of one element of any type (dim·nodes_per_element square, DOFs [u0x, u0y, (u0z,)
// u1x, ...]); per `thickness` in 2D, ignored in 3D. `nodes` holds nodes_per_element positions
// in the element's node order.
Eigen::MatrixXd element_stiffness(ElementType type, const Eigen::Vector3d* nodes, const ElementLaw& law,
                                  double thickness);
Eigen::MatrixXd element_stiffness(const Eigen::Vector2d* nodes, int order, const ElementLaw& law, double thickness);

// The element mean of the dilatation tr ε = ∂u_x/∂x + ∂u_y/∂y of a triangle: (1/|T|) ∫_T tr ε
// dA, for the element displacements ue (2·nodes, [u0x, u0y, ...]).
double element_mean_dilatation(const Eigen::Vector3d* nodes, int order, const Eigen::VectorXd& ue);
double element_mean_dilatation(const Eigen::Vector2d* nodes, int order, const Eigen::VectorXd& ue);

}  // namespace contactqp
