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

namespace {

// The agreements' own communicator (a copy of MPI_COMM_WORLD made when MPI starts alone), so
// that a failed rank's agreement can never be matched with a collective the others are in
// (sum_over_ranks' MPI_Allreduce on MPI_COMM_WORLD). MPI_COMM_WORLD when PETSc started MPI.
MPI_Comm agreement_communicator = MPI_COMM_NULL;

void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  // Freed before MPI_Finalize, which leaves a communicator still held to leak (LeakSanitizer).
  if (agreement_communicator != MPI_COMM_NULL) MPI_Comm_free(&agreement_communicator);
  MPI_Finalize();
}

}  // namespace

void connect_mpi() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized || MPI_Init(nullptr, nullptr) != MPI_SUCCESS) return;
  MPI_Comm_dup(MPI_COMM_WORLD, &agreement_communicator);
  // Registered before PETSc's PetscFinalize (which leaves MPI to whoever started it): runs after it.
  std::atexit(finalize_mpi);
}

AgreedFailure mpi_agree_on_failure(int status, const std::string& error, double timeout_seconds) {
  const int rank = mpi_rank();
  // The largest status, the lowest rank with an error (the largest −rank), and whether any rank
  // has none (then the error is that rank's own).
  int mine[3] = {status, error.empty() ? INT_MIN : -rank, error.empty() ? 1 : 0};
  int agreed[3] = {0, INT_MIN, 0};
  MPI_Request request = MPI_REQUEST_NULL;
  const MPI_Comm comm = agreement_communicator != MPI_COMM_NULL ? agreement_communicator : MPI_COMM_WORLD;
  MPI_Iallreduce(mine, agreed, 3, MPI_INT, MPI_MAX, comm, &request);
  const auto start = std::chrono::steady_clock::now();
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) break;
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!error.empty() && waited > timeout_seconds) {
      // The others are stuck where this rank left them: the last resort. The line goes out in one
      // write, before MPI_Abort: written in pieces, mpirun's own abort notice once landed between
      // them.
      const std::string line =
          "contactqp: error: " + error + " (on rank " + std::to_string(rank) + "; the other ranks did not finish)\n";
      std::cerr << line << std::flush;
      MPI_Abort(MPI_COMM_WORLD, status != 0 ? status : 1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(error.empty() ? 1 : 10));
  }
  AgreedFailure out;
  out.status = agreed[0];
  if (agreed[1] == INT_MIN) return out;
  // Every rank is in this agreement now: the first error reaches them all.
  out.process = -agreed[1];
  out.everywhere = agreed[2] == 0;
  out.error = rank == out.process ? error : std::string();
  int length = static_cast<int>(out.error.size());
  MPI_Bcast(&length, 1, MPI_INT, out.process, comm);
  out.error.resize(length);
  MPI_Bcast(out.error.data(), length, MPI_CHAR, out.process, comm);
  return out;
}

void start_petsc_runtime(const std::map<std::string, std::string>& library_options) {
  std::lock_guard<std::mutex> lock(petsc_mutex());
  PetscRuntime::instance(petsc_options_of(library_options));
}

}  // namespace contactqp::detail
