#include "sph_solver/parallel/halo.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "common/parallel/collective.hpp"

namespace tankfsi::sph {

namespace {

/// A half-open box with min >= max on some axis holds no point (an empty group's share).
bool holds_nothing(const Eigen::AlignedBox3d& box) { return (box.min().array() >= box.max().array()).any(); }

/// Squared Euclidean distance between two boxes that hold points (0 if they touch);
/// the same value whichever comes first, so both ranks of a pair agree.
double squared_gap(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  double sum = 0.0;
  for (Eigen::Index axis = 0; axis < 3; ++axis) {
    double gap = 0.0;
    if (b.min()[axis] > a.max()[axis]) {
      gap = b.min()[axis] - a.max()[axis];
    } else if (a.min()[axis] > b.max()[axis]) {
      gap = a.min()[axis] - b.max()[axis];
    }
    sum += gap * gap;
  }
  return sum;
}

/// The other ranks whose boxes lie within radius of this rank's, ascending.
std::vector<int> candidate_partners(const DomainDecomposition& decomposition, double radius) {
  std::vector<int> candidates;
  const Eigen::AlignedBox3d& own = decomposition.box(decomposition.rank());
  if (holds_nothing(own)) return candidates;
  for (int r = 0; r < decomposition.rank_count(); ++r) {
    const Eigen::AlignedBox3d& other = decomposition.box(r);
    if (r != decomposition.rank() && !holds_nothing(other) && squared_gap(own, other) <= radius * radius) {
      candidates.push_back(r);
    }
  }
  return candidates;
}

std::string build_problem(MPI_Comm comm, const DomainDecomposition& decomposition,
                          std::span<const Eigen::Vector3d> owned_positions, double radius) {
  int comparison = MPI_UNEQUAL;
  MPI_Comm_compare(comm, decomposition.comm(), &comparison);
  if (comparison != MPI_IDENT && comparison != MPI_CONGRUENT) {
    return "the communicator does not hold the decomposition's ranks in its order";
  }
  if (!(std::isfinite(radius) && radius > 0.0)) return "halo radius must be positive and finite";
  for (std::size_t i = 0; i < owned_positions.size(); ++i) {
    if (decomposition.owner(owned_positions[i]) != decomposition.rank()) {
      return "particle " + std::to_string(i) + " lies outside this rank's box (migrate before building the halo)";
    }
  }
  return {};
}

}  // namespace

void Halo::build(MPI_Comm comm, const DomainDecomposition& decomposition,
                 std::span<const Eigen::Vector3d> owned_positions, double radius) {
  throw_if_any_rank_failed(comm, "halo", build_problem(comm, decomposition, owned_positions, radius));
  comm_ = comm;
  owned_count_ = static_cast<int>(owned_positions.size());

  const std::vector<int> candidates = candidate_partners(decomposition, radius);
  std::vector<Link> links(candidates.size());
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    links[c].rank = candidates[c];
    const Eigen::AlignedBox3d& target = decomposition.box(candidates[c]);
    for (std::size_t i = 0; i < owned_positions.size(); ++i) {
      if (target.squaredExteriorDistance(owned_positions[i]) <= radius * radius) links[c].send.push_back(static_cast<int>(i));
    }
  }

  // Every candidate pair swaps its counts (zero too): the pairs are symmetric.
  std::vector<int> send_counts(candidates.size());
  std::vector<int> receive_counts(candidates.size());
  std::vector<MPI_Request> requests;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    send_counts[c] = static_cast<int>(links[c].send.size());
    post_receive(std::as_writable_bytes(std::span(&receive_counts[c], 1)), candidates[c], message_tag::halo_count, comm,
                 requests);
    post_send(std::as_bytes(std::span(&send_counts[c], 1)), candidates[c], message_tag::halo_count, comm, requests);
  }
  wait_all(requests);

  links_.clear();
  ghost_count_ = 0;
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (links[c].send.empty() && receive_counts[c] == 0) continue;
    links[c].ghost_begin = ghost_count_;
    links[c].ghost_count = receive_counts[c];
    ghost_count_ += receive_counts[c];
    links_.push_back(std::move(links[c]));
  }
}

std::vector<int> Halo::partners() const {
  std::vector<int> ranks;
  for (const Link& link : links_) ranks.push_back(link.rank);
  return ranks;
}

}  // namespace tankfsi::sph
