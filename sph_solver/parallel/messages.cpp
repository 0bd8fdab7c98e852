#include "sph_solver/parallel/messages.hpp"

#include <climits>
#include <stdexcept>
#include <string>

namespace tankfsi::sph {

namespace {

int message_size(std::size_t bytes) {
  if (bytes > static_cast<std::size_t>(INT_MAX)) {
    throw std::length_error("point-to-point message of " + std::to_string(bytes) + " bytes exceeds 2^31 - 1 bytes");
  }
  return static_cast<int>(bytes);
}

}  // namespace

void post_receive(std::span<std::byte> buffer, int source, int tag, MPI_Comm comm, std::vector<MPI_Request>& requests) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Irecv(buffer.data(), message_size(buffer.size()), MPI_BYTE, source, tag, comm, &request);
  requests.push_back(request);
}

void post_send(std::span<const std::byte> buffer, int destination, int tag, MPI_Comm comm,
               std::vector<MPI_Request>& requests) {
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Isend(buffer.data(), message_size(buffer.size()), MPI_BYTE, destination, tag, comm, &request);
  requests.push_back(request);
}

void wait_all(std::vector<MPI_Request>& requests) {
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
  requests.clear();
}

}  // namespace tankfsi::sph
