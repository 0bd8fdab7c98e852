#pragma once
// Small collective helpers.
//
// broadcast_text: a string from one rank to all (length first, then bytes).
// first_problem_on_any_rank / throw_if_any_rank_failed: a check made on every
// rank before a collective operation. If one rank threw
// alone, the others would wait for it forever in the next collective call; so
// each rank reports what it found, and then every rank throws the same error.
#include <mpi.h>

#include <string>

namespace tankfsi {

/// Collective. Returns, on every rank, `root`'s `text`.
[[nodiscard]] std::string broadcast_text(MPI_Comm comm, std::string text, int root = 0);

/// Collective. `local_problem` is empty when this rank found nothing wrong.
/// Returns, on every rank, "" if no rank found a problem, else the message of
/// the lowest rank that did, followed by " (on rank k)".
[[nodiscard]] std::string first_problem_on_any_rank(MPI_Comm comm, const std::string& local_problem);

/// Collective. Throws std::invalid_argument("context: message (on rank k)")
/// on every rank if any rank found a problem.
void throw_if_any_rank_failed(MPI_Comm comm, const std::string& context, const std::string& local_problem);

}  // namespace tankfsi
