// The PETSc runtime's free functions (petsc_runtime.hpp), MPI as PETSc started it (mpi.hpp),
// and the runtime of several processes the generic code asks (processes.hpp: registered at the end).
#include "petsc_runtime.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <iostream>
#include <thread>

#include "contactqp/processes.hpp"
#include "mpi.hpp"
#include "qp/builtins.hpp"

namespace contactqp::detail {

std::string error_text(PetscErrorCode code) {
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string out = text ? text : "PETSc error " + std::to_string(code);
  if (specific && *specific) out += std::string(": ") + specific;
  std::replace(out.begin(), out.end(), '\n', ' ');
  return out;
}

std::vector<std::string> option_names(const std::string& text) {
  std::vector<std::string> names;
  std::istringstream words(text);
  std::string word;
  while (words >> word)
    if (word.size() > 1 && word[0] == '-' && (std::isalpha(static_cast<unsigned char>(word[1])) || word[1] == '_'))
      names.push_back(word.substr(1));
  return names;
}

std::string environment_options() {
  const char* text = std::getenv("PETSC_OPTIONS");
  return text ? text : "";
}

std::mutex& petsc_mutex() {
  static std::mutex mutex;
  return mutex;
}

bool petsc_finalized() {
  PetscBool finalized = PETSC_FALSE;
  PetscFinalized(&finalized);
  return finalized;
}

int mpi_rank() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  if (!initialized || finalized) return -1;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int mpi_size() {
  if (mpi_rank() < 0) return 0;
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

void sum_over_ranks(double* values, long n) {
  if (mpi_size() <= 1) return;
  // In pieces, since MPI counts are int.
  constexpr long kPiece = 1L << 28;
  for (long start = 0; start < n; start += kPiece)
    MPI_Allreduce(MPI_IN_PLACE, values + start, static_cast<int>(std::min(kPiece, n - start)), MPI_DOUBLE, MPI_SUM,
                  MPI_COMM_WORLD);
}

int mpi_agree_on_exit(int status, const std::string& error_line, double timeout_seconds) {
  const int rank = mpi_rank();
  // The largest status, and the lowest rank with a line (the largest −rank).
  int mine[2] = {status, error_line.empty() ? INT_MIN : -rank}, agreed[2] = {0, INT_MIN};
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(mine, agreed, 2, MPI_INT, MPI_MAX, MPI_COMM_WORLD, &request);
  const auto start = std::chrono::steady_clock::now();
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!error_line.empty() && waited > timeout_seconds) {
      // The others are stuck where this rank left them: the last resort.
      std::cerr << error_line << " (rank " << rank << "; the other ranks did not finish)\n" << std::flush;
      MPI_Abort(MPI_COMM_WORLD, status != 0 ? status : 1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(error_line.empty() ? 1 : 10));
  }
  if (!error_line.empty() && agreed[1] == -rank) std::cerr << error_line << "\n";
  return agreed[0];
}

}  // namespace contactqp::detail

// Which process this is and how the processes end together, once PETSc has started MPI; and
// how to start it, with the user's PETSc options on PETSc's command line.
CONTACTQP_BUILTIN(mpi_processes) {
  ProcessRuntime mpi;
  mpi.rank = mpi_rank;
  mpi.count = mpi_size;
  mpi.start = [](const std::map<std::string, std::string>& library_options) {
    std::lock_guard<std::mutex> lock(petsc_mutex());
    PetscRuntime::instance(petsc_options_of(library_options));
  };
  mpi.agree_on_exit = mpi_agree_on_exit;
  register_process_runtime(mpi);
}
