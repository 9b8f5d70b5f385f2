// contactqp solve SCENE.json: run_scene() (run.hpp), then the summary and the output files.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

#include "commands.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/number_format.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/processes.hpp"
#include "contactqp/run.hpp"
#include "contactqp/temporary_file.hpp"
#include "phase_memory.hpp"
#include "progress.hpp"

namespace contactqp::cli {

void apply_overrides(const SolveArguments& arguments, SolveOptions& options) {
  if (!arguments.backend.empty()) options.backend = parse_backend(arguments.backend, "--backend");
  if (arguments.tol_given) {
    require(arguments.tol > 0 && arguments.tol < 1, "--tol", arguments.tol, "must lie in (0, 1)");
    options.tol = arguments.tol;
  }
  if (!arguments.rho.empty()) options.set(parse_rho(arguments.rho, "--rho"));
  if (arguments.max_iterations_given) {
    require(arguments.max_iterations > 0, "--max-iterations", arguments.max_iterations, "must be positive");
    options.max_iterations = arguments.max_iterations;
  }
  options.verbose = arguments.verbose;
  if (!arguments.ordering.empty()) options.ordering = parse_ordering(arguments.ordering, "--ordering");
  if (!arguments.linear_solver.empty())
    options.linear_solver = parse_linear_solver(arguments.linear_solver, "--linear-solver");
  if (arguments.petsc_options_given) {
    // "--petsc-options= --verbose" hands CLI11 an empty value and it takes the next argument
    // instead: a value that starts with "--" is one of ours, not PETSc's.
    if (arguments.petsc_options.rfind("--", 0) == 0)
      throw InputError("--petsc-options",
                       "= \"" + arguments.petsc_options +
                           "\": is a contactqp option, not PETSc's; write --petsc-options=\"-ksp_type cg\"");
    options.library_options["petsc"] = arguments.petsc_options;  // the PETSc room reads it (docs/petsc.md)
  }
  add_backend_options(arguments.backend_options, options);
}

void check_distinct_outputs(const std::string& scene_path,
                            const std::vector<std::pair<std::string, std::string>>& outputs) {
  namespace fs = std::filesystem;
  std::error_code error;
  auto same = [&](const std::string& a, const std::string& b) {
    return fs::weakly_canonical(a, error) == fs::weakly_canonical(b, error);
  };
  for (size_t i = 0; i < outputs.size(); ++i) {
    const auto& [field, path] = outputs[i];
    if (path.empty()) continue;
    if (same(path, scene_path)) throw InputError(field, "= " + path + ": is the scene file; it would be overwritten");
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].second.empty() && same(path, outputs[j].second))
        throw InputError(field, "= " + path + ": the same file as " + outputs[j].first);
  }
}

namespace {

// --adapt and --max-dofs, over the scene's "adapt" (docs/adaptive.md).
void apply_adapt_overrides(const SolveArguments& arguments, Scene& scene) {
  if (arguments.adapt_given) {
    require(arguments.adapt > 0 && arguments.adapt < 1, "--adapt", arguments.adapt,
            "must lie in (0, 1): the relative energy error eta/sqrt(2E) wanted, 0.01 for 1%");
    if (!scene.adapt) scene.adapt = AdaptSpec{};
    scene.adapt->target = arguments.adapt;
  }
  if (arguments.max_dofs_given) {
    require(arguments.max_dofs > 0, "--max-dofs", arguments.max_dofs, "must be positive");
    if (!scene.adapt)
      throw InputError("--max-dofs",
                       "= " + std::to_string(arguments.max_dofs) +
                           ": is the budget of an adaptive run; give --adapt TARGET or the scene's adapt");
    scene.adapt->max_dofs = arguments.max_dofs;
  }
}

int run_solve(const SolveArguments& arguments) {
  // Every check of the input first: a run never computes what it cannot save.
  if (!arguments.json_path.empty()) check_output_path(arguments.json_path, "--json");
  if (!arguments.csv_path.empty()) check_output_path(arguments.csv_path, "--csv");
  if (!arguments.vtu_path.empty()) check_output_path(arguments.vtu_path, "--vtu");
  check_distinct_outputs(
      arguments.scene_path,
      {{"--json", arguments.json_path}, {"--csv", arguments.csv_path}, {"--vtu", arguments.vtu_path}});
  require(arguments.max_elements > 0, "--max-elements", arguments.max_elements, "must be positive");
  begin_phase("read");
  Scene scene = load_scene(arguments.scene_path);
  apply_overrides(arguments, scene.solver);
  if (arguments.no_estimate) scene.estimate = false;
  apply_adapt_overrides(arguments, scene);

  RunOptions options;
  options.build.max_elements = arguments.max_elements;
  options.no_contact = arguments.no_contact;
  // The petsc backend's one-body scenes take the distributed path on one process too, where it
  // models them (frictionless, no load steps: run/distributed_run.hpp); --distributed, which
  // asked for it, is now the default and kept for the scripts that pass it. The library's
  // default stays the one-process path, whose report holds u, the model and the QP whole.
  options.distributed = true;
  // A distributed run writes its ParaView file in pieces, one per process, joined by a .pvtu;
  // on one process its one piece may be the .vtu itself.
  const bool distributed = runs_distributed(scene, options);
  const bool parallel_file =
      arguments.vtu_path.size() > 5 && arguments.vtu_path.compare(arguments.vtu_path.size() - 5, 5, ".pvtu") == 0;
  const bool one_piece = distributed && process_count() == 1;
  if (!arguments.vtu_path.empty() && !one_piece && distributed != parallel_file)
    throw InputError("--vtu",
                     "= " + arguments.vtu_path +
                         (distributed ? ": a distributed run (petsc under mpirun) writes one piece per process, "
                                        "joined by a .pvtu file: name one"
                                      : ": a .pvtu file is written by a distributed run (petsc under mpirun or a "
                                        "one-body frictionless scene without load steps); name a .vtu file"));
  RunReport report;
  std::string memory_line;
  // Under mpirun rank 0 alone shows progress, prints and writes the result files; in a
  // distributed run every rank writes its piece of the ParaView file.
  const bool writer = process_rank() == 0;
  {
    ProgressLine progress(!arguments.quiet && writer);
    PhaseMemory memory;
    options.on_phase = [&progress, &memory, &arguments](const char* phase) {
      progress.set(phase);
      if (arguments.phase_memory) memory.start(phase);
    };
    report = run_scene(scene, options);
    // The output files: the CSV and the ParaView file, timed as "write", then the JSON, which
    // records that time. Each is written beside its target and renamed into place only once
    // every rank has got that far: a rank that failed meanwhile leaves no file.
    begin_phase("write");
    progress.set("write", 0);
    if (arguments.phase_memory) memory.start("write");
    std::vector<std::unique_ptr<TemporaryFile>> staged;
    const auto stage = [&staged](const std::string& path, const std::string& content) {
      staged.push_back(std::make_unique<TemporaryFile>(path));
      staged.back()->write(content);
    };
    const auto commit = [&staged] {
      checkpoint();
      for (const auto& file : staged) file->commit();
    };
    Stopwatch clock;
    // A distributed run's pieces of the ParaView file, one per rank (collective; they and the
    // .pvtu appear together or not at all, src/distributed/distributed_post.cpp).
    if (report.write_pieces && !arguments.vtu_path.empty()) report.write_pieces(arguments.vtu_path);
    if (!writer) {
      commit();  // meets rank 0's, where it renames its files into place
      // Each rank's own peaks, one line each (what a rank holds is the point of a distributed run).
      if (arguments.phase_memory) std::cerr << memory.finish(" (rank " + std::to_string(process_rank()) + ")");
      return report.result.status == Status::Converged ? 0 : 1;
    }
    const std::pair<const std::string*, std::string (*)(const RunReport&)> files[] = {
        {&arguments.csv_path, profile_csv}, {&arguments.vtu_path, vtu_document}};
    const int n_files = !arguments.json_path.empty() + !arguments.csv_path.empty() + !arguments.vtu_path.empty();
    int written = report.write_pieces && !arguments.vtu_path.empty();
    for (const auto& [path, document] : files) {
      if (path->empty() || (report.write_pieces && path == &arguments.vtu_path)) continue;
      stage(*path, document(report));
      progress.set("write", static_cast<double>(++written) / n_files);
    }
    // "write" goes before "total", which then covers it too (all but the JSON's own writing).
    const double write_seconds = clock.seconds();
    Timings timings;
    for (const auto& [phase, seconds] : report.timings.phases())
      if (phase != "total") timings.add(phase, seconds);
    timings.add("write", write_seconds);
    timings.add("total", report.timings.get("total") + write_seconds);
    report.timings = timings;
    if (!arguments.json_path.empty()) stage(arguments.json_path, result_json(report));
    commit();
    if (arguments.phase_memory) memory_line = memory.finish();
  }
  std::cerr << memory_line;  // after the progress line is erased
  for (const std::string& warning : report.warnings) std::cerr << "contactqp: warning: " << warning << "\n";
  std::cout << summary_table(report);
  // An adaptive run that stopped short of its target says so, and fails like an unconverged solve.
  if (report.adaptive && !report.adaptive->met) {
    std::cerr << "contactqp: adapt: target " << number(100 * report.adaptive->spec.target, 3)
              << "% not met: " << report.adaptive->stop << "\n";
    return 1;
  }
  return report.result.status == Status::Converged ? 0 : 1;
}

}  // namespace

void add_backend_options(const std::vector<std::string>& pairs, SolveOptions& options) {
  for (const std::string& pair : pairs) {
    const auto equals = pair.find('=');
    if (equals == std::string::npos || equals == 0)
      throw InputError("--backend-option", "= " + pair + ": must be key=value");
    options.backend_options[pair.substr(0, equals)] = pair.substr(equals + 1);
  }
}

CLI::Option* refuse_empty(CLI::Option* option) {
  const std::string name = option->get_name();
  return option->each([name](const std::string& value) {
    if (value.empty()) throw InputError(name, "= \"\": must not be empty (leave the option out for the default)");
  });
}

void add_linear_solver_options(CLI::App& command, SolveArguments& arguments) {
  refuse_empty(command.add_option(
      "--linear-solver", arguments.linear_solver,
      "Solver of K for the backends: cholmod (default, direct) or petsc (KSP, CG + GAMG by default)"));
  command
      .add_option("--petsc-options", arguments.petsc_options,
                  "PETSc options database entries, passed through unchanged, e.g. --petsc-options=\"-ksp_type minres\" "
                  "(over the scene's solver.petsc_options; PETSC_OPTIONS is read too)")
      ->each([&arguments](const std::string&) { arguments.petsc_options_given = true; });
}

void add_solve_command(CLI::App& app, int& exit_status) {
  auto arguments = std::make_shared<SolveArguments>();
  CLI::App* command =
      app.add_subcommand("solve", "Solve one scene and report contact pressure, certificate and Hertz errors");
  command->add_option("scene", arguments->scene_path, "Scene file (JSON)")->required();
  refuse_empty(command->add_option("--backend", arguments->backend,
                                   "Optimisation backend: " + backend_names() + " (overrides solver.backend)"));
  CLI::Option* tol =
      command->add_option("--tol", arguments->tol, "Relative tolerance of the stopping rule (default 1e-8)");
  refuse_empty(
      command->add_option("--rho", arguments->rho, "Uzawa step: auto, a number, or a fraction of rho_max like 0.5x"));
  CLI::Option* max_iterations =
      command->add_option("--max-iterations", arguments->max_iterations,
                          "Iteration limit (default 10000; uzawa on a frictional problem 50000)");
  refuse_empty(command->add_option("--json", arguments->json_path, "Write the result JSON here"));
  refuse_empty(command->add_option("--csv", arguments->csv_path, "Write the contact pressure profile CSV here"));
  refuse_empty(
      command->add_option("--vtu", arguments->vtu_path,
                          "Write the mesh, displacement, stresses, pressure and gap for ParaView (.vtu) here"));
  command->add_option("--max-elements", arguments->max_elements, "Refuse meshes with more triangles (default 4000000)");
  command->add_option("--backend-option", arguments->backend_options,
                      "key=value passed to the backend (repeatable); ipopt.key=value addresses one backend");
  command->add_flag("--verbose", arguments->verbose, "Let the backend print its log");
  command->add_flag("--phase-memory", arguments->phase_memory,
                    "Print the peak resident memory of each phase on stderr (Linux /proc)");
  command->add_flag("--quiet", arguments->quiet, "No progress line on stderr (shown on a terminal after 2 s)");
  refuse_empty(command->add_option("--ordering", arguments->ordering,
                                   "Fill-reducing ordering of K: amd (default), metis or auto"));
  add_linear_solver_options(*command, *arguments);
  command->add_flag("--distributed", arguments->distributed,
                    "Accepted and redundant: the petsc backend runs distributed (each process holding only its "
                    "part of the mesh, model and output) on one process too wherever that path models the scene");
  command->add_flag("--no-estimate", arguments->no_estimate,
                    "Skip the energy-error estimate after the solve (over the scene's \"estimate\"; docs/estimate.md)");
  CLI::Option* adapt = command->add_option(
      "--adapt", arguments->adapt,
      "Adaptive run: remesh where the error estimate is large until eta/sqrt(2E) <= this, e.g. 0.01 "
      "(over the scene's adapt.target; docs/adaptive.md)");
  CLI::Option* max_dofs = command->add_option(
      "--max-dofs", arguments->max_dofs, "Adaptive run: no mesh with more DOFs (over adapt.max_dofs, default 1000000)");
  command->add_flag("--no-contact", arguments->no_contact,
                    "Drop the contact rows: one linear solve of the same K (the reference for timings)");
  command->footer(backends_help());
  command->callback([arguments, tol, max_iterations, adapt, max_dofs, &exit_status] {
    arguments->tol_given = tol->count() > 0;
    arguments->adapt_given = adapt->count() > 0;
    arguments->max_dofs_given = max_dofs->count() > 0;
    arguments->max_iterations_given = max_iterations->count() > 0;
    exit_status = run_solve(*arguments);
  });
}

}  // namespace contactqp::cli
