#pragma once
// DomainDecomposition: which rank owns which part of space, by recursive coordinate
// bisection (RCB; Berger & Bokhari 1987, "A partitioning strategy for nonuniform
// problems on multiprocessors", IEEE Trans. Comput. C-36:570).
//
// Why RCB: every rank gets one axis-aligned box, so "who owns x" is a walk down a
// tree of cuts ceil(log2 P) deep, "whose particles can be within the kernel support of
// mine" follows from box-to-box distances that every rank can compute alone (the
// halo's neighbour lists need no communication), and a rebalance only moves cuts.
//
// The cut tree. The P ranks of the communicator are split into the first floor(P/2)
// and the other ceil(P/2), recursively, down to single ranks. A group is cut
// across the longest extent of its particles' bounding box (in 2D never along z;
// equal extents: the lowest axis), at the coordinate that puts the lower
// floor(P/2)/P of its particles, rounded to the nearest count, on the lower side.
// A point with coordinate < cut belongs to the lower ranks, >= cut to the upper ones:
// box(r) is the half-open box [min, max) on every axis, the outer faces are at
// -inf / +inf, the boxes tile space and every finite point has exactly one owner.
// (Eigen's AlignedBox::contains tests the closed box; on a face, ask owner().)
// Until the first balance(), rank 0 owns all of space.
//
// Finding a cut without gathering particles: a parallel selection of the k-th
// smallest coordinate. The search keeps an interval [lo, hi] of particle
// coordinates that holds it and, per step, counts the group's particles below the
// midpoint with MPI_Allreduce, then narrows the interval to the nearest particle
// coordinates on the correct side (so every step at least halves the interval and
// removes at least one distinct coordinate; each rank then visits only its particles
// still inside it). All groups of one tree level search at once, with one pair of
// reductions over the whole communicator per step, since particles need not yet sit
// on the ranks of their group. A search stops once the count below a trial cut is
// within the tolerance of the target, or at the exact k-th coordinate.
//
// Balance guarantee. With cut_tolerance tau, a group of n particles over P ranks
// puts on its lower side the ideal n floor(P/2)/P particles up to
//   max(tau n floor(P/2)/P, t/2) + 1/2,
// where t is the number of the group's particles with exactly the cut coordinate
// (particles on one plane cannot be split: a lattice plane stays together). A rank's
// count therefore differs from N/P (N particles in all) by at most the sum of these
// over its ceil(log2 P) ancestors: with distinct coordinates, imbalance() stays
// below about 1 + ceil(log2 P) tau, and tau = 0 gives every rank N/P particles up to
// ceil(log2 P). Measured on 10^5 and 10^6 random particles on 2-4 ranks: the default
// tau = 1e-3 gave imbalance() <= 1.0014, tau = 0 gave exactly equal counts.
//
// balance(), migrate() and imbalance() are collective over the communicator given to
// the constructor, which must outlive the object; the queries are local.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

#include "sph_solver/particles/particles.hpp"

namespace tankfsi::sph {

class DomainDecomposition {
 public:
  /// Throws std::invalid_argument unless dimension is 2 or 3 and 0 <= cut_tolerance < 1.
  DomainDecomposition(MPI_Comm comm, int dimension, double cut_tolerance = 1e-3);

  /// Collective: recomputes every cut from the particles every rank owns now (they
  /// need not lie in this rank's box). Throws std::invalid_argument on every rank if
  /// any rank has a coordinate that is not finite or, in 2D, z != 0.
  void balance(std::span<const Eigen::Vector3d> owned_positions);

  /// The cuts of the last balance(): axis and position of every inner node,
  /// the same on every rank (what a checkpoint keeps).
  [[nodiscard]] std::vector<double> cuts() const;
  /// Puts back cuts() of a decomposition of as many ranks; throws
  /// std::invalid_argument if they do not fit this one's tree.
  void restore_cuts(std::span<const double> cuts);

  /// The rank owning x (the same answer on every rank).
  [[nodiscard]] int owner(const Eigen::Vector3d& x) const;

  /// The box of `rank`: [min, max) on every axis, outer faces at +-infinity. Ranks of a
  /// group that had no particles to cut, but the first, get an empty box (min >= max).
  [[nodiscard]] const Eigen::AlignedBox3d& box(int rank) const { return boxes_[static_cast<std::size_t>(rank)]; }

  /// Collective: sends every particle to owner(position). This rank keeps its own in
  /// their order and appends the received ones by source rank, each source's in its
  /// order, so the result does not depend on message timing. The counts go by one
  /// MPI_Alltoall (an int per rank pair); the particles, point to point, only between
  /// ranks that exchange some.
  void migrate(Particles& particles) const;

  /// Collective: the largest owned count over the mean (1 when no rank owns any).
  [[nodiscard]] double imbalance(int owned_count) const;

  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int rank_count() const { return rank_count_; }
  [[nodiscard]] int dimension() const { return dimension_; }
  [[nodiscard]] double cut_tolerance() const { return cut_tolerance_; }

 private:
  /// A node of the cut tree: ranks first_rank .. first_rank + rank_count - 1. An inner
  /// node sends coordinate[axis] < cut to child `lower`, the rest to `upper`.
  struct Node {
    int first_rank = 0;
    int rank_count = 1;
    int axis = 0;
    double cut = 0.0;
    int lower = -1;  ///< -1 for a leaf
    int upper = -1;
  };

  void build_tree_shape();
  void cut_level(std::span<const Eigen::Vector3d> positions, std::span<const int> level_nodes,
                 std::vector<int>& node_of_particle);
  void compute_boxes(int index, const Eigen::AlignedBox3d& region);
  [[nodiscard]] const Node& node(int index) const { return nodes_[static_cast<std::size_t>(index)]; }

  MPI_Comm comm_;
  int rank_ = 0;
  int rank_count_ = 1;
  int dimension_;
  double cut_tolerance_;
  std::vector<Node> nodes_;              ///< breadth first, root at 0
  std::vector<int> level_begin_;         ///< nodes of level l: level_begin_[l] .. [l+1)
  std::vector<Eigen::AlignedBox3d> boxes_;  ///< by rank
};

}  // namespace tankfsi::sph
