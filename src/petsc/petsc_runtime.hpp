// The PETSc runtime shared by the PETSc solver of K (petsc_solver.cpp), the bound-constrained
// QP solver of the petsc backend (petsc_bound_qp.cpp) and the partition: PetscInitialize once
// per process, the options database handed from one user to the next, PETSc's error text, one
// lock. Internal to the room (cqp_petsc), like the other headers that include PETSc.
#pragma once

#include <petscsys.h>

#include <cstdlib>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contactqp/errors.hpp"

namespace contactqp::detail {

// The text of a PETSc error code, with the specific message of the last error.
std::string error_text(PetscErrorCode code);
// Throws std::runtime_error("<what>: <error_text>") when a PETSc call failed.
inline void check_petsc(PetscErrorCode code, const char* what) {
  if (code) throw std::runtime_error(std::string(what) + ": " + error_text(code));
}
// The names in an options string ("-ksp_type cg -pc_type gamg" -> ksp_type, pc_type).
std::vector<std::string> option_names(const std::string& text);
std::string environment_options();  // PETSC_OPTIONS, or ""
std::mutex& petsc_mutex();          // PETSc is not thread-safe: one call into it at a time
bool petsc_finalized();

// PETSc and MPI for the whole process. PETSc's options database is process-wide too: the
// options of the solver set up last are the ones in it (earlier strings are cleared, the
// environment's re-inserted), so solvers built one after another in one process do not see
// each other's options.
class PetscRuntime {
 public:
  // Initialises on first use with `options` as its command line, so that process-wide options
  // (-log_view, -info, -malloc_debug) take effect as PETSc users expect. Throws InputError
  // when PETSc cannot start.
  static PetscRuntime& instance(const std::string& options) {
    // Never destroyed: PETSc holds pointers into its argv until PetscFinalize, at exit.
    static PetscRuntime* runtime = new PetscRuntime(options);
    return *runtime;
  }

  // Changes whenever the database changes hands: a solver checks for unused options only
  // while the database still holds what it was set up with.
  long generation() const { return generation_; }

  // Puts `options` (and PETSC_OPTIONS) in the database in place of the previous solver's.
  void use_options(const std::string& options) {
    if (options == current_) return;
    for (const std::string& name : option_names(current_)) PetscOptionsClearValue(nullptr, ("-" + name).c_str());
    const std::string environment = environment_options();
    if (!environment.empty()) PetscOptionsInsertString(nullptr, environment.c_str());
    const PetscErrorCode code = PetscOptionsInsertString(nullptr, options.c_str());
    if (code) throw InputError("petsc_options", "= \"" + options + "\": " + error_text(code));
    current_ = options;
    ++generation_;
  }

  // The options of `options` and PETSC_OPTIONS that nothing has read (PETSc's -options_left).
  std::vector<std::string> unused(const std::string& options) const {
    std::set<std::string> ours;
    for (const std::string& name : option_names(options)) ours.insert(name);
    for (const std::string& name : option_names(environment_options())) ours.insert(name);
    // Read only by PetscFinalize (or at start-up): not "unused" while a solve runs.
    for (const char* late : {"options_left", "log_view", "memory_view", "malloc_dump", "malloc_view", "objects_dump",
                             "malloc_debug", "info", "skip_petscrc", "no_signal_handler", "help"})
      ours.erase(late);
    std::vector<std::string> out;
    PetscInt n = 0;
    char** names = nullptr;
    char** values = nullptr;
    if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return out;
    for (PetscInt i = 0; i < n; ++i) {
      std::string name = names[i] ? names[i] : "";
      if (!name.empty() && name[0] == '-') name.erase(0, 1);
      if (ours.count(name)) out.push_back("-" + name + (values[i] ? std::string(" ") + values[i] : std::string()));
    }
    PetscOptionsLeftRestore(nullptr, &n, &names, &values);
    return out;
  }

 private:
  explicit PetscRuntime(const std::string& options) : current_(options) {
    PetscBool initialized = PETSC_FALSE;
    PetscInitialized(&initialized);
    if (!initialized) {
      // PETSc keeps pointers to argv: the strings live as long as the runtime.
      arguments_.push_back("contactqp");
      std::istringstream words(options);
      std::string word;
      while (words >> word) arguments_.push_back(word);
      for (std::string& argument : arguments_) argv_.push_back(argument.data());
      argv_.push_back(nullptr);
      argc_ = static_cast<int>(arguments_.size());
      char** argv = argv_.data();
      const PetscErrorCode code = PetscInitialize(&argc_, &argv, nullptr, nullptr);
      if (code)
        throw InputError("linear_solver", "= \"petsc\": PETSc could not start (error " + std::to_string(code) + ")");
      std::atexit(finalize);
    } else {
      PetscOptionsInsertString(nullptr, options.c_str());
    }
    // Errors come back as codes and become our messages; no tracebacks on stderr. PETSc's
    // signal handler would turn a crash elsewhere in the program into a PETSc message.
    PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    PetscPopSignalHandler();
  }

  static void finalize() {
    PetscBool finalized = PETSC_TRUE;
    PetscFinalized(&finalized);
    if (!finalized) PetscFinalize();
  }

  std::string current_;
  long generation_ = 0;
  std::vector<std::string> arguments_;
  std::vector<char*> argv_;
  int argc_ = 0;
};

}  // namespace contactqp::detail
