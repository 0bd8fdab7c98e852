#pragma once
// Halo: the ghost particles of one rank — copies of other ranks' particles close
// enough to this rank's box to be within the kernel support of one of its own —
// and the exchange of any per-particle field onto them.
//
// Which particles: every particle whose Euclidean distance to this rank's (closed)
// box is <= radius, for a radius the caller chooses (the kernel support plus a
// margin for the motion until the next build). Near a box corner this is a ball, not
// a slab. A particle near several other ranks' boxes is a ghost on each of them.
// A particle owned here lies inside this rank's box, so anything within `radius` of
// one of them lies within `radius` of the box: the halo holds every neighbour a
// search with that radius can find.
//
// With whom: two ranks can exchange only if their boxes are within `radius` of
// each other, which every rank computes from the decomposition alone; build() then
// swaps send counts with those candidates only, and the exchanges talk to the ranks
// with something to send or receive — non-blocking point-to-point, no all-to-all.
//
// Layout: a field of owned + ghost entries, owned first (in the caller's order),
// then the ghosts by source rank, each source's in its owned order. The order is
// deterministic, so two runs on the same ranks exchange the same values in the same
// slots, and accumulate() adds the ghosts' contributions in a fixed order.
//
// The halo is a snapshot: rebuild it whenever the owned particles change (after a
// migration, a reorder, or motion beyond the margin). Every member function except
// the accessors is collective over the communicator given to build(), which must
// outlive the halo's use.
#include <Eigen/Core>
#include <mpi.h>

#include <cassert>
#include <cstddef>
#include <span>
#include <vector>

#include "sph_solver/parallel/domain_decomposition.hpp"
#include "sph_solver/parallel/messages.hpp"

namespace tankfsi::sph {

class Halo {
 public:
  /// Collective. owned_positions: this rank's particles, all inside its box (after
  /// DomainDecomposition::migrate). Throws std::invalid_argument on every rank if any
  /// rank passes a radius that is not positive and finite or a particle it does not
  /// own, or if comm is not the decomposition's group of ranks.
  void build(MPI_Comm comm, const DomainDecomposition& decomposition, std::span<const Eigen::Vector3d> owned_positions,
             double radius);

  [[nodiscard]] int owned_count() const { return owned_count_; }
  [[nodiscard]] int ghost_count() const { return ghost_count_; }
  /// Ranks this rank sends to or receives from, ascending.
  [[nodiscard]] std::vector<int> partners() const;

  /// Collective. Reads field[0 .. owned_count()), sends the values other ranks need
  /// and stores the received ones: on exit field.size() == owned_count() + ghost_count().
  template <HaloValue T>
  void exchange(std::vector<T>& field) const;

  /// Collective, the reverse of exchange(): field holds owned_count() + ghost_count()
  /// entries; each ghost's value is sent back to its owner and added to the owner's
  /// entry (sources by rank, then in ghost order). Ghost entries are left unchanged.
  template <HaloValue T>
    requires requires(T& sum, const T& term) { sum += term; }
  void accumulate(std::vector<T>& field) const;

 private:
  /// The traffic with one other rank.
  struct Link {
    int rank = 0;
    std::vector<int> send;  ///< owned indices whose values go to `rank`, ascending
    int ghost_begin = 0;    ///< its particles' slots: ghost_begin .. ghost_begin + ghost_count - 1
    int ghost_count = 0;    ///< (counted from the first ghost)
  };

  [[nodiscard]] std::size_t ghost_slot(const Link& link, int k) const {
    return static_cast<std::size_t>(owned_count_ + link.ghost_begin + k);
  }

  MPI_Comm comm_ = MPI_COMM_NULL;
  int owned_count_ = 0;
  int ghost_count_ = 0;
  std::vector<Link> links_;  ///< by rank, only ranks with traffic
};

template <HaloValue T>
void Halo::exchange(std::vector<T>& field) const {
  assert(field.size() >= static_cast<std::size_t>(owned_count_));
  using W = WireType<T>;
  std::vector<std::vector<W>> incoming(links_.size());
  std::vector<std::vector<W>> outgoing(links_.size());
  std::vector<MPI_Request> requests;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    if (links_[l].ghost_count == 0) continue;
    incoming[l].resize(static_cast<std::size_t>(links_[l].ghost_count));
    post_receive(std::as_writable_bytes(std::span(incoming[l])), links_[l].rank, message_tag::halo_exchange, comm_,
                 requests);
  }
  for (std::size_t l = 0; l < links_.size(); ++l) {
    if (links_[l].send.empty()) continue;
    outgoing[l].reserve(links_[l].send.size());
    for (const int i : links_[l].send) outgoing[l].push_back(Wire<T>::to_wire(field[static_cast<std::size_t>(i)]));
    post_send(std::as_bytes(std::span(outgoing[l])), links_[l].rank, message_tag::halo_exchange, comm_, requests);
  }
  wait_all(requests);

  field.resize(static_cast<std::size_t>(owned_count_ + ghost_count_));
  for (std::size_t l = 0; l < links_.size(); ++l) {
    for (int k = 0; k < links_[l].ghost_count; ++k) {
      field[ghost_slot(links_[l], k)] = Wire<T>::from_wire(incoming[l][static_cast<std::size_t>(k)]);
    }
  }
}

template <HaloValue T>
  requires requires(T& sum, const T& term) { sum += term; }
void Halo::accumulate(std::vector<T>& field) const {
  assert(field.size() == static_cast<std::size_t>(owned_count_ + ghost_count_));
  using W = WireType<T>;
  std::vector<std::vector<W>> incoming(links_.size());
  std::vector<std::vector<W>> outgoing(links_.size());
  std::vector<MPI_Request> requests;
  for (std::size_t l = 0; l < links_.size(); ++l) {
    if (links_[l].send.empty()) continue;
    incoming[l].resize(links_[l].send.size());
    post_receive(std::as_writable_bytes(std::span(incoming[l])), links_[l].rank, message_tag::halo_accumulate, comm_,
                 requests);
  }
  for (std::size_t l = 0; l < links_.size(); ++l) {
    if (links_[l].ghost_count == 0) continue;
    outgoing[l].reserve(static_cast<std::size_t>(links_[l].ghost_count));
    for (int k = 0; k < links_[l].ghost_count; ++k) outgoing[l].push_back(Wire<T>::to_wire(field[ghost_slot(links_[l], k)]));
    post_send(std::as_bytes(std::span(outgoing[l])), links_[l].rank, message_tag::halo_accumulate, comm_, requests);
  }
  wait_all(requests);

  for (std::size_t l = 0; l < links_.size(); ++l) {
    for (std::size_t k = 0; k < incoming[l].size(); ++k) {
      field[static_cast<std::size_t>(links_[l].send[k])] += Wire<T>::from_wire(incoming[l][k]);
    }
  }
}

}  // namespace tankfsi::sph
