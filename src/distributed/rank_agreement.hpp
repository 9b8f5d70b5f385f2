// Steps that may fail on some ranks only (rank 0 cannot read the mesh file; one rank's part of
// the mesh holds a bad value), ended the same way on every rank: no rank goes on alone into
// the next collective call while another has stopped, so a failure never hangs the run.
#pragma once

#include <functional>

namespace contactqp::detail {

// Runs `step` on this rank, then every rank learns whether any rank's step threw. If one did,
// every rank throws the lowest failing rank's error: an InputError as an InputError (the same
// field and text, so the run exits 2 with that one line), anything else as a
// std::runtime_error with its text and the rank. Collective (MPI_COMM_WORLD).
void agree_on_step(const std::function<void()>& step);

// The same for a step only rank 0 does (meshing the coarse body): the others wait for its outcome.
void agree_on_rank_zero(const std::function<void()>& step);

}  // namespace contactqp::detail
