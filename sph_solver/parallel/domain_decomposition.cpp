#include "sph_solver/parallel/domain_decomposition.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "common/parallel/collective.hpp"
#include "sph_solver/parallel/messages.hpp"

namespace tankfsi::sph {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

std::size_t at(int index) { return static_cast<std::size_t>(index); }

Eigen::AlignedBox3d whole_space() {
  return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-infinity), Eigen::Vector3d::Constant(infinity));
}

std::string position_problem(std::span<const Eigen::Vector3d> positions, int dimension) {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!positions[i].allFinite()) return "particle " + std::to_string(i) + " has a coordinate that is not finite";
    if (dimension == 2 && positions[i].z() != 0.0) return "particle " + std::to_string(i) + " of a 2D run has z != 0";
  }
  return {};
}

std::int64_t miss(std::int64_t count, std::int64_t target) { return count > target ? count - target : target - count; }

/// The smallest cut with every particle at coordinate <= x below it.
double just_above(double x) { return std::nextafter(x, infinity); }

/// The search for one group's cut along one axis (see the header: parallel selection).
/// While it runs, below_lo <= target < through_hi.
struct CutSearch {
  int axis = 0;
  std::int64_t target = 0;      ///< particles wanted below the cut
  std::int64_t tolerance = 0;   ///< accepted miss of the target, in particles
  double lo = 0.0;              ///< lo and hi are particle coordinates with
  double hi = 0.0;              ///< the target-th smallest coordinate in [lo, hi]
  std::int64_t below_lo = 0;    ///< particles with coordinate < lo
  std::int64_t through_hi = 0;  ///< particles with coordinate <= hi
  double mid = 0.0;             ///< the current step's trial cut
  double cut = 0.0;
  bool done = false;
};

/// Ends the search if a cut at lo or just above hi is good enough, or if no
/// particle coordinate is left between them (then the closer of the two; a tie goes to lo).
void settle(CutSearch& search) {
  if (miss(search.below_lo, search.target) <= search.tolerance) {
    search.cut = search.lo;
  } else if (miss(search.through_hi, search.target) <= search.tolerance) {
    search.cut = just_above(search.hi);
  } else if (search.lo == search.hi) {
    const bool lo_closer = search.target - search.below_lo <= search.through_hi - search.target;
    search.cut = lo_closer ? search.lo : just_above(search.hi);
  } else {
    return;
  }
  search.done = true;
}

/// The axis of the longest extent among the first `dimension` axes (the lowest on ties).
int longest_axis(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper, int dimension) {
  int axis = 0;
  for (int a = 1; a < dimension; ++a) {
    if (upper[a] - lower[a] > upper[axis] - lower[axis]) axis = a;
  }
  return axis;
}

// Each group's particle count and bounding box (two reductions for the whole level)
// give its axis, its target count and the initial interval.
// group_ranks[s]: the rank count of the group in slot s.
std::vector<CutSearch> start_searches(MPI_Comm comm, std::span<const Eigen::Vector3d> positions,
                                      std::span<const int> slot_of_particle, std::span<const int> group_ranks,
                                      int dimension, double cut_tolerance) {
  const std::size_t groups = group_ranks.size();
  std::vector<std::int64_t> counts(groups, 0);
  std::vector<double> bounds(6 * groups, -infinity);  // per group: -min (3), max (3), all by MPI_MAX
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (slot_of_particle[i] < 0) continue;
    const std::size_t s = at(slot_of_particle[i]);
    ++counts[s];
    for (std::size_t a = 0; a < 3; ++a) {
      const double x = positions[i][static_cast<Eigen::Index>(a)];
      bounds[6 * s + a] = std::max(bounds[6 * s + a], -x);
      bounds[6 * s + 3 + a] = std::max(bounds[6 * s + 3 + a], x);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, counts.data(), static_cast<int>(groups), MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, bounds.data(), static_cast<int>(6 * groups), MPI_DOUBLE, MPI_MAX, comm);

  std::vector<CutSearch> searches(groups);
  for (std::size_t s = 0; s < groups; ++s) {
    CutSearch& search = searches[s];
    const std::int64_t n = counts[s];
    if (n == 0) {  // an empty group: its lower ranks keep its whole region
      search.cut = infinity;
      search.done = true;
      continue;
    }
    const std::int64_t ranks = group_ranks[s];
    const std::int64_t lower_ranks = ranks / 2;
    const Eigen::Vector3d lower(-bounds[6 * s], -bounds[6 * s + 1], -bounds[6 * s + 2]);
    const Eigen::Vector3d upper(bounds[6 * s + 3], bounds[6 * s + 4], bounds[6 * s + 5]);
    search.axis = longest_axis(lower, upper, dimension);
    search.target = (2 * n * lower_ranks + ranks) / (2 * ranks);  // n lower_ranks / ranks, rounded
    search.tolerance = static_cast<std::int64_t>(
        std::floor(cut_tolerance * static_cast<double>(n) * static_cast<double>(lower_ranks) / static_cast<double>(ranks)));
    search.lo = lower[search.axis];
    search.hi = upper[search.axis];
    search.below_lo = 0;
    search.through_hi = n;
    settle(search);
  }
  return searches;
}

// One step of every running search: count below the midpoint of [lo, hi] and find
// the particle coordinates next to it on either side (two reductions for the level).
// Only the candidates — this rank's particles in [lo, hi] of a running search — are
// visited: those below lo are already counted in below_lo.
void search_step(MPI_Comm comm, std::span<const Eigen::Vector3d> positions, std::span<const int> slot_of_particle,
                 std::span<const int> candidates, std::vector<CutSearch>& searches) {
  for (CutSearch& search : searches) {
    if (search.done) continue;
    search.mid = std::midpoint(search.lo, search.hi);
    if (!(search.mid > search.lo)) search.mid = search.hi;  // lo and hi adjacent doubles
  }
  const std::size_t groups = searches.size();
  std::vector<std::int64_t> below(groups, 0);
  std::vector<double> nearest(2 * groups, -infinity);  // per group: max below mid, -min at or above mid
  for (const int i : candidates) {
    const std::size_t s = at(slot_of_particle[at(i)]);
    const double x = positions[at(i)][searches[s].axis];
    if (x < searches[s].mid) {
      ++below[s];
      nearest[2 * s] = std::max(nearest[2 * s], x);
    } else {
      nearest[2 * s + 1] = std::max(nearest[2 * s + 1], -x);
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, below.data(), static_cast<int>(groups), MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, nearest.data(), static_cast<int>(2 * groups), MPI_DOUBLE, MPI_MAX, comm);

  for (std::size_t s = 0; s < groups; ++s) {
    CutSearch& search = searches[s];
    if (search.done) continue;
    below[s] += search.below_lo;
    if (miss(below[s], search.target) <= search.tolerance) {
      search.cut = search.mid;
      search.done = true;
      continue;
    }
    // Particles exist on the side kept (below_lo <= target < through_hi), so the
    // reduced coordinate there is finite and within [lo, hi].
    if (below[s] <= search.target) {
      search.lo = -nearest[2 * s + 1];
      search.below_lo = below[s];
    } else {
      search.hi = nearest[2 * s];
      search.through_hi = below[s];
    }
    settle(search);
  }
}

/// Drops the candidates whose search has ended or that left its [lo, hi].
void narrow(std::vector<int>& candidates, std::span<const Eigen::Vector3d> positions,
            std::span<const int> slot_of_particle, const std::vector<CutSearch>& searches) {
  std::erase_if(candidates, [&](int i) {
    const CutSearch& search = searches[at(slot_of_particle[at(i)])];
    const double x = positions[at(i)][search.axis];
    return search.done || x < search.lo || x > search.hi;
  });
}

/// What a particle travels as when it changes rank: every field of Particles.
struct MigrantRecord {
  std::int64_t id;
  std::array<double, 3> position;
  std::array<double, 3> velocity;
  double mass;
  double pressure;
};
static_assert(std::is_trivially_copyable_v<MigrantRecord>);

MigrantRecord pack(const Particles& particles, std::size_t i) {
  return MigrantRecord{particles.id[i], Wire<Eigen::Vector3d>::to_wire(particles.position[i]),
                       Wire<Eigen::Vector3d>::to_wire(particles.velocity[i]), particles.mass[i],
                       particles.pressure[i]};
}

void unpack(const MigrantRecord& record, Particles& particles) {
  particles.push_back(record.id, Wire<Eigen::Vector3d>::from_wire(record.position),
                      Wire<Eigen::Vector3d>::from_wire(record.velocity), record.mass, record.pressure);
}

}  // namespace

DomainDecomposition::DomainDecomposition(MPI_Comm comm, int dimension, double cut_tolerance)
    : comm_(comm), dimension_(dimension), cut_tolerance_(cut_tolerance) {
  if (dimension != 2 && dimension != 3) {
    throw std::invalid_argument("domain decomposition: dimension must be 2 or 3, got " + std::to_string(dimension));
  }
  if (!(cut_tolerance >= 0.0 && cut_tolerance < 1.0)) {
    throw std::invalid_argument("domain decomposition: cut tolerance must lie in [0, 1)");
  }
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &rank_count_);
  build_tree_shape();
  boxes_.assign(at(rank_count_), Eigen::AlignedBox3d());
  compute_boxes(0, whole_space());
}

// Nodes breadth first; every inner node starts with its cut at +infinity on x, so
// that everything goes to its lower half: rank 0 owns all of space.
void DomainDecomposition::build_tree_shape() {
  nodes_.assign(1, Node{0, rank_count_, 0, infinity, -1, -1});
  level_begin_.assign(1, 0);
  while (at(level_begin_.back()) < nodes_.size()) {
    const std::size_t begin = at(level_begin_.back());
    const std::size_t end = nodes_.size();
    level_begin_.push_back(static_cast<int>(end));
    for (std::size_t n = begin; n < end; ++n) {
      const int first = nodes_[n].first_rank;
      const int count = nodes_[n].rank_count;
      if (count == 1) continue;
      const int lower_count = count / 2;
      nodes_[n].lower = static_cast<int>(nodes_.size());
      nodes_[n].upper = static_cast<int>(nodes_.size()) + 1;
      nodes_.push_back(Node{first, lower_count, 0, infinity, -1, -1});
      nodes_.push_back(Node{first + lower_count, count - lower_count, 0, infinity, -1, -1});
    }
  }
}

void DomainDecomposition::balance(std::span<const Eigen::Vector3d> owned_positions) {
  throw_if_any_rank_failed(comm_, "domain decomposition", position_problem(owned_positions, dimension_));
  std::vector<int> node_of_particle(owned_positions.size(), 0);
  for (std::size_t level = 0; level + 1 < level_begin_.size(); ++level) {
    std::vector<int> inner_nodes;
    for (int n = level_begin_[level]; n < level_begin_[level + 1]; ++n) {
      if (node(n).lower >= 0) inner_nodes.push_back(n);
    }
    if (!inner_nodes.empty()) cut_level(owned_positions, inner_nodes, node_of_particle);
  }
  compute_boxes(0, whole_space());
}

std::vector<double> DomainDecomposition::cuts() const {
  std::vector<double> values;
  for (const Node& n : nodes_)
    if (n.lower >= 0) {
      values.push_back(n.axis);
      values.push_back(n.cut);
    }
  return values;
}

void DomainDecomposition::restore_cuts(std::span<const double> cuts) {
  std::size_t inner = 0;
  for (const Node& n : nodes_) inner += n.lower >= 0 ? 1 : 0;
  if (cuts.size() != 2 * inner)
    throw std::invalid_argument("DomainDecomposition::restore_cuts: " + std::to_string(cuts.size() / 2) +
                                " cuts for a tree of " + std::to_string(inner));
  std::size_t k = 0;
  for (Node& n : nodes_)
    if (n.lower >= 0) {
      n.axis = static_cast<int>(cuts[k]);
      n.cut = cuts[k + 1];
      k += 2;
    }
  compute_boxes(0, whole_space());
}

// Cuts every inner node of one level, then moves each of its particles to a child.
void DomainDecomposition::cut_level(std::span<const Eigen::Vector3d> positions, std::span<const int> level_nodes,
                                    std::vector<int>& node_of_particle) {
  std::vector<int> slot_of_node(nodes_.size(), -1);
  for (std::size_t s = 0; s < level_nodes.size(); ++s) slot_of_node[at(level_nodes[s])] = static_cast<int>(s);
  std::vector<int> slot_of_particle(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) slot_of_particle[i] = slot_of_node[at(node_of_particle[i])];

  std::vector<int> group_ranks;
  for (const int n : level_nodes) group_ranks.push_back(node(n).rank_count);
  std::vector<CutSearch> searches =
      start_searches(comm_, positions, slot_of_particle, group_ranks, dimension_, cut_tolerance_);
  std::vector<int> candidates;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (slot_of_particle[i] >= 0) candidates.push_back(static_cast<int>(i));
  }
  narrow(candidates, positions, slot_of_particle, searches);
  while (std::any_of(searches.begin(), searches.end(), [](const CutSearch& s) { return !s.done; })) {
    search_step(comm_, positions, slot_of_particle, candidates, searches);
    narrow(candidates, positions, slot_of_particle, searches);
  }

  for (std::size_t s = 0; s < level_nodes.size(); ++s) {
    nodes_[at(level_nodes[s])].axis = searches[s].axis;
    nodes_[at(level_nodes[s])].cut = searches[s].cut;
  }
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (slot_of_particle[i] < 0) continue;
    const Node& parent = node(node_of_particle[i]);
    node_of_particle[i] = positions[i][parent.axis] < parent.cut ? parent.lower : parent.upper;
  }
}

// A cut outside the region (only +infinity, for an empty group) is clamped to it,
// which keeps every box inside its parent's.
void DomainDecomposition::compute_boxes(int index, const Eigen::AlignedBox3d& region) {
  const Node& n = node(index);
  if (n.lower < 0) {
    boxes_[at(n.first_rank)] = region;
    return;
  }
  Eigen::AlignedBox3d lower = region;
  Eigen::AlignedBox3d upper = region;
  lower.max()[n.axis] = std::min(region.max()[n.axis], n.cut);
  upper.min()[n.axis] = std::max(region.min()[n.axis], n.cut);
  compute_boxes(n.lower, lower);
  compute_boxes(n.upper, upper);
}

int DomainDecomposition::owner(const Eigen::Vector3d& x) const {
  int index = 0;
  while (node(index).lower >= 0) {
    const Node& n = node(index);
    index = x[n.axis] < n.cut ? n.lower : n.upper;
  }
  return node(index).first_rank;
}

void DomainDecomposition::migrate(Particles& particles) const {
  std::vector<int> kept;
  std::vector<std::vector<MigrantRecord>> outgoing(at(rank_count_));
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const int destination = owner(particles.position[i]);
    if (destination == rank_) {
      kept.push_back(static_cast<int>(i));
    } else {
      outgoing[at(destination)].push_back(pack(particles, i));
    }
  }
  std::vector<int> send_counts(at(rank_count_));
  for (std::size_t r = 0; r < outgoing.size(); ++r) send_counts[r] = static_cast<int>(outgoing[r].size());
  std::vector<int> receive_counts(at(rank_count_));
  MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm_);

  std::vector<std::vector<MigrantRecord>> incoming(at(rank_count_));
  std::vector<MPI_Request> requests;
  for (int r = 0; r < rank_count_; ++r) {
    if (receive_counts[at(r)] == 0) continue;
    incoming[at(r)].resize(at(receive_counts[at(r)]));
    post_receive(std::as_writable_bytes(std::span(incoming[at(r)])), r, message_tag::migration, comm_, requests);
  }
  for (int r = 0; r < rank_count_; ++r) {
    if (outgoing[at(r)].empty()) continue;
    post_send(std::as_bytes(std::span(outgoing[at(r)])), r, message_tag::migration, comm_, requests);
  }
  wait_all(requests);

  particles.reorder(kept);
  for (const auto& from_rank : incoming) {
    for (const MigrantRecord& record : from_rank) unpack(record, particles);
  }
}

double DomainDecomposition::imbalance(int owned_count) const {
  const std::int64_t local = owned_count;
  std::int64_t largest = 0;
  std::int64_t total = 0;
  MPI_Allreduce(&local, &largest, 1, MPI_INT64_T, MPI_MAX, comm_);
  MPI_Allreduce(&local, &total, 1, MPI_INT64_T, MPI_SUM, comm_);
  if (total == 0) return 1.0;
  return static_cast<double>(largest) * static_cast<double>(rank_count_) / static_cast<double>(total);
}

}  // namespace tankfsi::sph
