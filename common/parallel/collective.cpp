#include "common/parallel/collective.hpp"

#include <climits>
#include <stdexcept>

namespace tankfsi {

std::string broadcast_text(MPI_Comm comm, std::string text, int root) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, comm);
  text.resize(static_cast<std::size_t>(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, root, comm);
  return text;
}

std::string first_problem_on_any_rank(MPI_Comm comm, const std::string& local_problem) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int my_claim = local_problem.empty() ? INT_MAX : rank;
  int reporting_rank = INT_MAX;
  MPI_Allreduce(&my_claim, &reporting_rank, 1, MPI_INT, MPI_MIN, comm);
  if (reporting_rank == INT_MAX) return {};

  // Only the reporting rank knows its message: send it to everyone, so that
  // every rank's log says what went wrong, not just that something did.
  const std::string message = broadcast_text(comm, rank == reporting_rank ? local_problem : std::string(), reporting_rank);
  return message + " (on rank " + std::to_string(reporting_rank) + ")";
}

void throw_if_any_rank_failed(MPI_Comm comm, const std::string& context, const std::string& local_problem) {
  if (const auto problem = first_problem_on_any_rank(comm, local_problem); !problem.empty())
    throw std::invalid_argument(context + ": " + problem);
}

}  // namespace tankfsi
