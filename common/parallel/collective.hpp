#pragma once
// Small collective helpers.
//
// broadcast_text: a string from one rank to all (length first, then bytes).
// first_problem_on_any_rank / throw_if_any_rank_failed: a check made on every
// rank before a collective operation. If one rank threw
// alone, the others would wait for it forever in the next collective call; so
// each rank reports what it found, and then every rank throws the same error.
// run_on_root: work one rank does for all (the probe files), with its failure
// made every rank's the same way.
#include <mpi.h>

#include <exception>
#include <stdexcept>
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

/// Collective. Calls `work` on rank `root` alone; if it throws, every rank throws
/// std::runtime_error with its message (and " (on rank root)").
template <class Work>
void run_on_root(MPI_Comm comm, int root, Work&& work) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string problem;
  if (rank == root) {
    try {
      work();
    } catch (const std::exception& e) {
      problem = *e.what() != '\0' ? e.what() : "an error without a message";
    }
  }
  if (const auto found = first_problem_on_any_rank(comm, problem); !found.empty()) throw std::runtime_error(found);
}

}  // namespace tankfsi
