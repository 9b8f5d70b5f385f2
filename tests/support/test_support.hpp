// Helpers shared by the tests: small QPs with exact solutions, running the CLI.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "contactqp/post.hpp"
#include "contactqp/qp.hpp"
#include "contactqp/scene.hpp"
#include "qp/norms.hpp"

namespace contactqp::testing {

// A QP from dense data (K symmetric positive definite).
QuadraticProgram make_qp(const Eigen::MatrixXd& K, const Eigen::VectorXd& f, const Eigen::MatrixXd& B,
                         const Eigen::VectorXd& g);

// The stiffness of masses 0..n−1 on a line joined by springs k[i] (mass i to i+1), mass 0
// grounded by a spring `ground` (0: the chain floats, K singular with the translation
// (1, ..., 1) in its kernel).
Eigen::MatrixXd chain_of_springs(const std::vector<double>& k, double ground = 0);

// One spring of stiffness k pulled by F towards a wall at distance `gap`:
// u = min(F/k, gap), λ = max(0, F − k·gap) — the wall pushes back, so λ ≥ 0 is compression.
QuadraticProgram spring_against_wall(double k, double F, double gap);

// The exact solution of a small QP by enumerating every active set (m ≤ 12): for each set A,
// solve the equality-constrained KKT system and keep the one that is primal and dual feasible.
struct ExactSolution {
  Eigen::VectorXd u, lambda;
};
ExactSolution solve_by_enumeration(const QuadraticProgram& qp);

// A random strictly convex QP with n variables and m constraints, reproducible from `seed`,
// whose solution has some constraints active and some not.
QuadraticProgram random_qp(int n, int m, unsigned seed);

// The norms and relative differences (relative_difference, relative_error, ...) the tests
// compare against tolerances are the library's own, src/qp/norms.hpp, included above.

// Options for `backend` at tolerance `tol`, with enough iterations for the small test problems.
SolveOptions options_for(Backend backend, double tol);

// Path of a file in the source tree, e.g. source_path("scenes/hertz.json").
std::string source_path(const std::string& relative);
std::string read_text(const std::string& path);

// Runs the contactqp executable with `arguments` (a shell-quoted string).
struct CliRun {
  int exit_status = -1;
  std::string out, err;
};
CliRun run_cli(const std::string& arguments);

// A fresh temporary directory for one test, removed by the destructor.
class TemporaryDirectory {
 public:
  TemporaryDirectory();
  ~TemporaryDirectory();
  std::string path(const std::string& name) const { return directory_ + "/" + name; }

 private:
  std::string directory_;
};

// The names of the files in a directory, sorted: a failed run must leave it as it was (no
// result, no temporary file).
std::vector<std::string> directory_listing(const std::string& directory);

// A unit square of two 3-node triangles with its sides named "bottom", "right", "top", "left"
// and the surface "body": a .msh file (Gmsh 2.2, ASCII) for tests to break in one way each.
extern const char* const kUnitSquareMsh;

// The shipped scene with some JSON patched in, e.g. patch_scene("scenes/hertz.json",
// R"({"material": {"E": 1e9}})") merges like JSON Merge Patch (RFC 7386).
std::string patched_scene(const std::string& relative, const std::string& merge_patch);

// A bad scene for the input tests: its whole text and what the one-line message must name.
struct BadScene {
  std::string text;   // a whole scene
  std::string names;  // what the one-line message must contain
};

// A scene built, solved with its own solver options, and post-processed.
struct SceneRun {
  Model model;
  QuadraticProgram qp;
  SolveResult result;
  ContactSummary contact;
  std::vector<Reaction> reactions;
};
SceneRun solve_scene(const Scene& scene);

// A shipped scene (relative to the source tree) with a JSON merge patch, parsed as if it
// were in scenes/ (so its mesh file resolves), solved.
SceneRun solve_scene(const std::string& relative, const std::string& merge_patch = "{}");

// The QP of a shipped scene with a JSON merge patch, parsed as if it were in scenes/.
QuadraticProgram scene_qp(const std::string& relative, const std::string& merge_patch = "{}");

}  // namespace contactqp::testing
