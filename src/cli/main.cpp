// contactqp: the command-line tool. Thin: parses the command line and runs a subcommand.
// Only main() catches everything; bad input exits 2 with one line on stderr.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.hpp"
#include "contactqp/errors.hpp"
#include "contactqp/phases.hpp"
#include "contactqp/processes.hpp"

int main(int argc, char** argv) {
  // Launched as several processes (mpirun): connected first, so that a failure on one of them,
  // anywhere, is heard (src/run/phases.hpp).
  if (contactqp::process_count() > 1) contactqp::connect_processes();
  CLI::App app{"contactqp: contact of elastic bodies with rigid obstacles, frictionless or with friction, as QPs"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "contactqp 0.1.0");
  int exit_status = 0;
  contactqp::cli::add_solve_command(app, exit_status);
  contactqp::cli::add_compare_command(app, exit_status);
  contactqp::cli::add_mesh_command(app, exit_status);
  if (argc > 1 && argv[1][0] != '-') {
    std::string valid;
    bool known = false;
    for (const CLI::App* command : app.get_subcommands({})) {
      valid += (valid.empty() ? "" : ", ") + command->get_name();
      known = known || command->get_name() == argv[1];
    }
    if (!known) {
      std::cerr << "contactqp: error: \"" << argv[1] << "\" is not a command; valid: " << valid << " (see --help)\n";
      return 2;
    }
  }
  // Every way out goes through agree_on_failure (processes.hpp): under mpirun all ranks end with
  // the same status and the error line is printed once, by the first rank that has one.
  std::string error;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const contactqp::FailedElsewhere& failed) {
    // Another process failed and printed the line; the agreement is made.
    std::cout << std::flush;
    return failed.status();
  } catch (const CLI::ParseError& parse) {
    // One line, like every other bad input.
    std::string text = parse.what();
    std::replace(text.begin(), text.end(), '\n', ' ');
    error = text + " (see --help)";
    exit_status = 2;
  } catch (const contactqp::InputError& bad) {
    error = bad.what();
    exit_status = 2;
  } catch (const std::bad_alloc&) {
    error = "out of memory; try a coarser mesh";
    exit_status = 1;
  } catch (const std::exception& failure) {
    error = failure.what();
    exit_status = 1;
  }
  std::cout << std::flush;
  const contactqp::AgreedFailure agreed =
      contactqp::agree_on_failure(exit_status, error, contactqp::failed_process_grace_seconds());
  // The first process with an error speaks for the run, naming itself when not every one failed.
  // In one write: under mpirun another process's output must not land inside the line.
  if (!error.empty() && agreed.process == contactqp::process_rank())
    std::cerr << "contactqp: error: " + error +
                     (agreed.everywhere ? std::string() : " (on rank " + std::to_string(agreed.process) + ")") + "\n";
  return agreed.status;
}
