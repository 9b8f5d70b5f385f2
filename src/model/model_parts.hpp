// The steps of build_model (model.cpp composes them), each in its own file.
#pragma once

#include <functional>

#include "contactqp/model.hpp"
#include "fe/loads.hpp"
#include "mesh/refine.hpp"

namespace contactqp::detail {

// model.cpp: the candidate distance (model.max_gap, max_gap_rule): the scene's, or one that
// follows from the loads.
void choose_max_gap(const Scene& scene, Model& model);
// model.cpp: a warning when the elements lock for this Poisson's ratio; the mesh turned by the
// scene's transform.
void warn_near_incompressible(const Scene& scene, const Mesh& mesh, std::vector<std::string>& warnings);
void rotate_mesh(Mesh& mesh, const Eigen::Matrix3d& rotation);

// body_mesh.cpp: the body's mesh in the scene's own frame — a generated shape refined where
// contact can happen (initial gap ≤ max_gap), or a Gmsh file. InputError when it would
// exceed options.max_elements or cannot be made.
Mesh mesh_body(const Scene& scene, double max_gap, const BuildOptions& options);

// The same in two steps, for a distributed run (src/distributed/): what Gmsh meshes, checked
// as the body's mesh will be (its order, dimension, refined element count), and the body's
// mesh from it or from a part of it (InputError("body.mesh", ...) when refining fails).
CoarseMesh coarse_body_mesh(const Scene& scene, double max_gap, const BuildOptions& options);
Mesh refine_body_mesh(const CoarseMesh& coarse, const Mesh& part, NodeParents* parents = nullptr);
// How the scene's coarse mesh is refined (its mesh left empty), known without meshing: what
// the ranks that do not mesh need to refine their parts alike.
CoarseMesh body_refinement(const Scene& scene);

// bodies_model.cpp: build_model() for a scene with several bodies (scene.bodies).
Model build_bodies_model(const Scene& scene, const BuildOptions& options);

// mesh_names.cpp: every boundary, region and point the scene names exists in the mesh (the
// names of a mesh body are known only now); the symmetry boundary of a mesh body lies on x = 0.
void check_mesh_names(const Scene& scene, const Mesh& mesh);

// boundary_conditions.cpp: free_index, prescribed and DOF frames from the displacement loads
// and the symmetry plane. `rotation` is the scene's transform: with a rotation, prescribed
// components stay along the scene's own axes.
void apply_displacement_conditions(Model& model, const Scene& local_scene, const Eigen::Matrix3d& rotation);
// The same with the nodes of a boundary given by `nodes_of` (a distributed mesh's part knows a
// node is on a boundary even where the face that puts it there is another rank's).
using NodesOfBoundary = std::function<std::vector<int>(const std::string& boundary)>;
void apply_displacement_conditions(Model& model, const Scene& local_scene, const Eigen::Matrix3d& rotation,
                                   const NodesOfBoundary& nodes_of);
// The force a rigid surface carries on the modelled part (its whole-body force over the body's
// symmetry copies), and all of them as nodal forces in DOF components (dim·n_nodes): each at
// its surface's first node, since K and f see the surface's DOFs only through their one column.
double rigid_surface_share(const Model& model, const RigidSurface& surface);
Eigen::VectorXd rigid_surface_forces(const Model& model);

// turning_surfaces.cpp: the force loads with a moment (model.rigid_rotations, model.levers):
// one column per axis a surface turns about, numbered after every other column (so a scene
// without a moment keeps its numbering), and each tied DOF's lever arm on it, (frame column
// c)·(axis × (x − centre)). A turn that moves the tied DOFs only as a translation would (a lever
// arm of 0, or equal at every node) is an InputError naming the moment.
void turn_rigid_surfaces(Model& model, const Scene& scene, const Eigen::Matrix3d& rotation,
                         const NodesOfBoundary& nodes_of);

// rigid_motions.cpp: InputError naming the free motions (translations, rotations about a
// point in 2D or an axis in 3D) and what would hold them, unless the prescribed DOFs (in their DOF frames)
// hold every connected part of the mesh against rigid motion. Before any assembly: a free
// body's K is singular.
void check_rigid_motions(const Model& model);

// The rigid motions each connected part of the mesh keeps free (rigid_motions.cpp), in rigid
// coordinates: (t_x, t_y, r) in 2D, the rotation r about the centroid scaled by the extent;
// (t, ω) in 3D, the displacement t + ω × (x − centre)/extent.
struct PartFreedom {
  int first_node = -1;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the part's centroid (z = 0 in 2D)
  double extent = 1;                                 // the largest distance of a node from it (1 when 0)
  Eigen::MatrixXd null;                              // 3 × k or 6 × k: the motions nothing prescribed stops
};
struct RigidFreedom {
  std::vector<int> part;  // the part of each node
  std::vector<PartFreedom> parts;
};
RigidFreedom rigid_freedom(const Model& model);
// The displacement at x of the motion with rigid coordinates `rigid` of `part` (z = 0 in 2D).
Eigen::Vector3d rigid_motion_at(const PartFreedom& part, const Eigen::VectorXd& rigid, const Eigen::Vector3d& x,
                                int dim);
// One motion in words, signed: "along +y", "along (0.6, 0.8)", "by rotation about (0, 2), clockwise".
std::string describe_motion(const Model& model, const PartFreedom& part, const Eigen::VectorXd& rigid);
// check_rigid_motions' InputError for part p and the motions `null`, saying `why` they are refused.
inline constexpr const char* kNothingHolds =
    "no prescribed displacement stops it, so K is singular, and contact alone does not hold a body here";
[[noreturn]] void refuse_free_part(const Model& model, const RigidFreedom& freedom, int p, const Eigen::MatrixXd& null,
                                   const std::string& why);

// held_by_contact.cpp: the free rigid motions of a one-body model that its contact candidates
// can hold (docs/extremes.md, "Bodies held only by their contacts"). InputError as
// check_rigid_motions when a free motion that the load drives (`scene_force`: the nodal forces
// in the scene frame, as the model stands before it is turned; called only when a motion is
// free) is seen by no candidate row: nothing
// could ever stop it. Returns the free motions, one column each, as displacements at every
// node (dim·n_nodes × k, scene axes); zero columns when the prescribed DOFs hold the body.
Eigen::MatrixXd motions_held_by_contact(Model& model, const std::function<Eigen::VectorXd()>& scene_force);
// Those motions on the free DOFs of the turned model (n_free × k; each node's DOF frame and the
// scene's rotation applied): K's null space, which assemble_qp puts in qp.null_space.
Eigen::MatrixXd free_modes_on_dofs(const Model& model, const Eigen::MatrixXd& at_nodes);

// load_shares.cpp: each load's share (model.hpp's LoadShare) on the model's mesh: its nodal
// forces (point loads at point_nodes[l]) and the DOFs it prescribes, for the loads of
// model.scene (global frame; displacement values along the DOF frames).
std::vector<LoadShare> load_shares(const Model& model, const std::vector<int>& point_nodes);
// The same with each boundary's nodes from `nodes_of` and load l's nodal forces from
// `nodal_force(l)` (a distributed run's part: its faces' and elements' forces, the nodes of a
// boundary whichever rank holds its faces).
std::vector<LoadShare> load_shares(const Model& model, const NodesOfBoundary& nodes_of,
                                   const std::function<Eigen::VectorXd(std::size_t load)>& nodal_force);

// assembly.cpp: force loads into f over the free DOFs: f_a += Tᵀ f_x at each node (T its DOF frame, f_x
// model.nodal_force); forces at prescribed DOFs go to the reactions.
void add_force_loads(const Model& model, Eigen::VectorXd& f);

// assembly.cpp: InputError when K (its largest entry, whether all are finite) or f leave double precision:
// units so far from one that the numbers overflow or lose their digits.
void refuse_unrepresentable(const Model& model, double largest_k, bool k_finite, double largest_f, bool f_finite);

// assembly.cpp: model.prescribed and model.nodal_force for one load step, the loads'
// shares scaled by `factors` (apply_load_step's first half; the rigid surfaces' forces too).
// InputError naming `step` when two loads then prescribe one DOF to different values.
void set_step_loads(Model& model, const std::vector<double>& factors, const std::string& step);

}  // namespace contactqp::detail
