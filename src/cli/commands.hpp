// The subcommands of the contactqp tool. Each returns the process exit status:
// 0 converged, 1 any other solver outcome, 2 bad input (thrown as InputError, caught in main).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "contactqp/io.hpp"
#include "contactqp/number_format.hpp"

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace contactqp::cli {

// Options shared by the commands that solve a scene.
struct SolveArguments {
  std::string scene_path;
  std::string backend;  // empty: the scene's solver.backend
  double tol = 0;
  bool tol_given = false;  // otherwise the scene's solver.tol
  std::string rho;         // empty: the scene's
  int max_iterations = 0;
  bool max_iterations_given = false;
  std::string json_path, csv_path, vtu_path;
  long long max_elements = BuildOptions{}.max_elements;
  bool verbose = false;
  bool quiet = false;         // solve: no progress line
  bool phase_memory = false;  // solve: the peak memory of each phase on stderr
  bool no_contact = false;    // drop the contact rows: one linear solve of the same K
  bool no_estimate = false;   // skip the energy-error estimate (the scene's "estimate": false)
  double adapt = 0;           // the adaptive run's target (the scene's adapt.target), when given
  bool adapt_given = false;
  long long max_dofs = 0;  // the adaptive run's DOF budget (adapt.max_dofs), when given
  bool max_dofs_given = false;
  bool distributed = false;   // solve: the distributed path on one process too (petsc)
  std::string ordering;       // empty: SolveOptions' default (amd)
  std::string linear_solver;  // empty: the scene's solver.linear_solver (default cholmod)
  std::string petsc_options;  // PETSc options database entries, passed through unchanged
  bool petsc_options_given = false;
  std::vector<std::string> backend_options;  // key=value
};

void add_solve_command(CLI::App& app, int& exit_status);
// An option whose empty value would read as "not given" (--json "", --backend ""): given empty, it
// is bad input naming the option, not silently ignored.
CLI::Option* refuse_empty(CLI::Option* option);
// --linear-solver and --petsc-options, shared by solve and compare.
void add_linear_solver_options(CLI::App& command, SolveArguments& arguments);
void add_compare_command(CLI::App& app, int& exit_status);
void add_mesh_command(CLI::App& app, int& exit_status);  // mesh_command.cpp

// The command line's solver settings over the scene's (InputError on a bad value).
void apply_overrides(const SolveArguments& arguments, SolveOptions& options);
// --backend-option key=value pairs into options.backend_options (over the scene's own).
void add_backend_options(const std::vector<std::string>& pairs, SolveOptions& options);

// InputError when an output path is the scene file or another output's path (field, path pairs;
// empty paths are not asked for).
void check_distinct_outputs(const std::string& scene_path,
                            const std::vector<std::pair<std::string, std::string>>& outputs);

// backend_help.cpp: the available backends' names ("uzawa, uzawa_accel, ..."), and every
// registered backend with its summary and options, one per line, for the help's footer.
std::string backend_names();
std::string backends_help();

// The human summary printed on stdout after a solve.
std::string summary_table(const RunReport& report);

}  // namespace contactqp::cli
