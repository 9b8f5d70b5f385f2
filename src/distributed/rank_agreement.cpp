// agree_on_step() (rank_agreement.hpp).
#include "rank_agreement.hpp"

#include <mpi.h>

#include <climits>
#include <stdexcept>
#include <string>

#include "contactqp/errors.hpp"

namespace contactqp::detail {
namespace {

enum Kind { kNone = 0, kInput = 1, kOther = 2 };

void broadcast_text(std::string& text, int root) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, MPI_COMM_WORLD);
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, root, MPI_COMM_WORLD);
}

}  // namespace

void agree_on_step(const std::function<void()>& step) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int kind = kNone;
  std::string field, text;
  try {
    step();
  } catch (const InputError& error) {
    kind = kInput;
    field = error.field();
    text = error.what();
  } catch (const std::exception& error) {
    kind = kOther;
    text = error.what();
  }
  // The lowest failing rank speaks for all.
  int mine = kind == kNone ? INT_MAX : rank, first = INT_MAX;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  if (first == INT_MAX) return;
  MPI_Bcast(&kind, 1, MPI_INT, first, MPI_COMM_WORLD);
  broadcast_text(field, first);
  broadcast_text(text, first);
  if (kind == kInput) {
    // InputError's text is "field message": rebuild it from its two parts, unchanged.
    const std::string message = text.size() > field.size() ? text.substr(field.size() + 1) : std::string();
    throw InputError(field, message);
  }
  throw std::runtime_error(text + (first != 0 ? " (on rank " + std::to_string(first) + ")" : std::string()));
}

void agree_on_rank_zero(const std::function<void()>& step) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  agree_on_step([&] {
    if (rank == 0) step();
  });
}

}  // namespace contactqp::detail
