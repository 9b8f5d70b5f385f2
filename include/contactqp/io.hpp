// Output files: the result JSON, the pressure profile CSV, written atomically.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contactqp/certificate.hpp"
#include "contactqp/estimate.hpp"
#include "contactqp/post.hpp"
#include "contactqp/scene.hpp"

namespace contactqp {

// Throws InputError(field, ...) when `path` cannot be written: its directory is missing or
// not writable, or the path is a directory. Call before any work, so that a run never
// computes a result it cannot save.
void check_output_path(const std::string& path, const std::string& field);

// Writes to a temporary file beside `path`, then renames it over `path`: readers see the old
// file or the complete new one, never a half-written one. Throws std::runtime_error on failure
// (and removes the temporary file).
void write_file_atomically(const std::string& path, const std::string& content);

// The whole problem's size, whichever process holds what of it.
struct ProblemSize {
  long long nodes = 0, elements = 0, dofs = 0, constraints = 0;
};

// One load step of a run with steps (scene.steps, docs/friction.md): what it solved and the
// contact it gave, post-processed as the run's last state is.
struct StepReport {
  std::string path;                                     // "steps[1]"
  std::vector<std::pair<std::string, double>> factors;  // every named load's factor at the step's end
  Status status = Status::NumericalError;
  std::string message;
  int iterations = 0;
  double seconds = 0;  // the step's solve
  std::map<std::string, double> diagnostics;
  ContactSummary contact;
  std::vector<PairContact> pairs;
  std::vector<Reaction> reactions;
};

// One cycle of an adaptive run (docs/adaptive.md): the mesh it solved on and what it gave.
struct AdaptiveCycle {
  long long elements = 0, dofs = 0;
  double estimate = 0;  // η
  double relative = 0;  // η / sqrt(2E)
  double strain_energy = 0;
  // Against the obstacles (ContactSummary); in a scene whose bodies touch only each other, the
  // first pair's (PairContact: the force's norm, the node side's pressure).
  double total_force = 0, max_pressure = 0;
  double zone = 0;  // the contact zone's half-width b (2D) or radius a (3D)
  // With friction (the last load step's): the tangential force Q and the stick zone's half-width
  // c (2D) or radius (3D), from the same zone as the three above.
  bool friction = false;
  double tangential_force = 0, stick_zone = 0;
  int iterations = 0;  // the solve's (started from the last cycle's answer after the first)
  double seconds = 0;  // the cycle's whole run: mesh to estimate
};

// An adaptive run's cycles, in order; the report around it is the last cycle's.
struct AdaptiveRun {
  AdaptSpec spec;
  bool met = false;  // the last cycle's η / sqrt(2E) is at most spec.target
  std::string stop;  // why it stopped short of the target; "" when met
  std::vector<AdaptiveCycle> cycles;
};

// Everything one solve produced, for the result file and the summary. run_scene() (run.hpp)
// makes one. The report owns what it holds, the model and the QP included (shared, read-only),
// so that it outlives the scene it came from, e.g. as a Python object.
struct RunReport {
  std::shared_ptr<const Model> model;
  std::shared_ptr<const QuadraticProgram> qp;
  SolveOptions options;  // as solved: the scene's solver section with the caller's overrides
  SolveResult result;
  Certificate certificate;
  ContactSummary contact;
  std::optional<HertzComparison> hertz;
  std::optional<PunchComparison> boussinesq;  // 3D scenes pressed by a flat punch
  std::vector<Reaction> reactions;            // one per displacement load
  std::vector<FloatingBody> floating;         // each body only its contacts hold: how far it moved
  std::vector<PairContact> pairs;             // one per contact pair of a scene with bodies
  std::optional<FrictionFields> friction;     // each row's friction, with friction (the last step's)
  std::vector<StepReport> steps;              // each load step in order; empty without steps
  Timings timings;                            // every phase: mesh, assemble, factorize, solve, ..., total
  bool no_contact = false;                    // a linear solve with the contact rows dropped (--no-contact)
  std::vector<std::string> warnings;          // also printed on stderr
  ProblemSize size;                           // the mesh's nodes and elements, the QP's DOFs and rows
  // ½ uᵀKu of the whole displacement (ErrorEstimate::strain_energy) and the energy-error estimate
  // (docs/estimate.md): a one-process run has both, the estimate unless the scene's "estimate"
  // is false (--no-estimate); a distributed run neither.
  std::optional<double> strain_energy;
  std::optional<ErrorEstimate> error_estimate;
  // An adaptive run (scene "adapt"): every cycle; the rest of the report is the last cycle's,
  // its timings the last cycle's phases, "adapt" (the earlier cycles) and "total" (all of them).
  std::optional<AdaptiveRun> adaptive;
  // A run whose processes each hold part of the mesh (mpirun, src/distributed/) writes its
  // ParaView file in pieces: every process calls this with the .pvtu path (collective), which
  // writes its piece beside it and, on the first process, the .pvtu. Empty otherwise.
  std::function<void(const std::string& pvtu_path)> write_pieces;
};

// The result JSON (docs/cli.md, "Result file"). Numbers that are not finite are written as null.
std::string result_json(const RunReport& report);

// The pressure profile: s, pressure, nodal force, Hertz's pressure when it applies, obstacle.
std::string profile_csv(const RunReport& report);

// The mesh and the solution as a VTK XML unstructured grid (ParaView's .vtu): 3-node or
// 6-node triangles (VTK_TRIANGLE, VTK_QUADRATIC_TRIANGLE) or 4-node or 10-node tetrahedra
// (VTK_TETRA, VTK_QUADRATIC_TETRA), point data "displacement" (3 components, z = 0 in 2D),
// "sigma_xx", "sigma_yy", "sigma_xy", "sigma_zz" (3D also "sigma_yz", "sigma_xz"), "von_mises",
// "contact_pressure" and "contact_force" (3 components, the obstacles' force on the body),
// "gap" (on the contact boundary: the row's slack g − Bu at candidates, the deformed distance
// to the nearest obstacle elsewhere; 0 off it) and "contact_boundary" (1 on it, 0 off it); cell
// data "error_indicator" (each element's η_T, docs/estimate.md) when the run has an estimate.
// Binary (base64) arrays; no NaN.
std::string vtu_document(const RunReport& report);

// The pieces of vtu_document(), for a ParaView file written in pieces (one per MPI rank, each
// its rank's elements and their nodes; src/distributed/): one array at the nodes (Float64,
// `components` per node, n_points × components values from `values`, or from `storage`).
struct PointArray {
  std::string name;
  int components = 1;
  const double* values = nullptr;
  std::vector<double> storage;  // when the array was made for the file (2D vectors as 3 components)
};
// Pressure, contact force (dim per node), gap and the contact-boundary mask at every node.
struct ContactFields {
  Eigen::VectorXd pressure, force, gap, mask;
};
// vtu_document()'s arrays, in its order, of a model's nodes ("body" only when given).
std::vector<PointArray> solution_arrays(const Model& model, const Eigen::VectorXd& displacement,
                                        const NodalStress& stress, const ContactFields& contact,
                                        const Eigen::VectorXd* body = nullptr);
// A VTK XML unstructured grid (.vtu) of `mesh` with `arrays`, as vtu_document() writes it, and
// `cell_arrays` at its elements (`components` per element, e.g. "error_indicator").
std::string vtu_piece(const Mesh& mesh, const std::vector<PointArray>& arrays,
                      const std::vector<PointArray>& cell_arrays = {});
// The parallel file (.pvtu) that joins pieces with these arrays (their values are not read):
// `pieces` are the piece files' names relative to the .pvtu; `cell_arrays` the pieces' cell data.
std::string pvtu_document(const std::vector<PointArray>& arrays, const std::vector<std::string>& pieces,
                          const std::vector<PointArray>& cell_arrays = {});

}  // namespace contactqp
