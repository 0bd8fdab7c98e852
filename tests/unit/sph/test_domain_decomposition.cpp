// Domain decomposition and halo against brute force: random clouds and lattices in
// 2D and 3D, scattered over the ranks, balanced and migrated; then every particle
// is owned exactly once, by the rank whose box holds it, in the documented order;
// each rank's count is within the stated balance bound; owner() agrees with the
// half-open boxes, on box faces too; a second balance gives the same boxes. The halo
// of each rank equals, as an ordered list of ids, every other rank's particle within
// the radius of its box (Euclidean distance, so corners are balls), fields of
// several types arrive in those slots, and accumulate() returns each ghost's value
// to its owner. Every rank gathers all particles to build the expected answers.
// Run on 1-4 ranks; MPI_COMM_SELF gives the one-rank case on every run.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include "common/parallel/mpi_session.hpp"
#include "sph_solver/parallel/domain_decomposition.hpp"
#include "sph_solver/parallel/halo.hpp"

using namespace tankfsi::sph;
using tankfsi::comm_info;

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

std::size_t at(int index) { return static_cast<std::size_t>(index); }
std::size_t at(std::int64_t index) { return static_cast<std::size_t>(index); }

// Uniform in [0, 1) from the top 53 bits of the engine, the same on every platform.
double uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

// Random points in [0, 2) x [0, 1.6) x [0, 1.2) (z = 0 in 2D): squarish, so 3 and 4
// ranks cut along two axes and boxes meet at corners.
std::vector<Eigen::Vector3d> random_cloud(std::uint64_t seed, int count, int dimension) {
  std::mt19937_64 engine(seed);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double x = 2.0 * uniform(engine);
    const double y = 1.6 * uniform(engine);
    const double z = 1.2 * uniform(engine);
    points.emplace_back(x, y, dimension == 3 ? z : 0.0);
  }
  return points;
}

// A lattice of spacing 1/16 (dyadic: every coordinate and distance below is exact).
std::vector<Eigen::Vector3d> lattice(int nx, int ny, int nz) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      for (int k = 0; k < nz; ++k) points.emplace_back(0.0625 * i, 0.0625 * j, 0.0625 * k);
    }
  }
  return points;
}

// Where particle g starts: scattered, so that almost every particle has to move.
int first_holder(std::size_t g, int ranks) { return static_cast<int>((g * 7 + 3) % static_cast<std::size_t>(ranks)); }

Eigen::Vector3d velocity_of(std::int64_t id) {
  const auto v = static_cast<double>(id);
  return Eigen::Vector3d(v, -2.0 * v, 0.0);
}
double mass_of(std::int64_t id) { return 1.0 + static_cast<double>(id); }
double pressure_of(std::int64_t id) { return 2.0 * static_cast<double>(id); }

// This rank's initial share of the global set: ids are indices into `all`.
Particles initial_share(const std::vector<Eigen::Vector3d>& all, int rank, int ranks) {
  Particles particles;
  for (std::size_t g = 0; g < all.size(); ++g) {
    if (first_holder(g, ranks) != rank) continue;
    const auto id = static_cast<std::int64_t>(g);
    particles.push_back(id, all[g], velocity_of(id), mass_of(id), pressure_of(id));
  }
  return particles;
}

// Every rank's particles on every rank, in rank order, each rank's in its order.
struct Everyone {
  std::vector<int> counts;
  std::vector<int> rank_of;
  std::vector<std::int64_t> ids;
  std::vector<Eigen::Vector3d> positions;
};

Everyone gather(MPI_Comm comm, const Particles& particles) {
  const int ranks = comm_info(comm).size;
  Everyone all;
  all.counts.resize(at(ranks));
  const int mine = particles.count();
  MPI_Allgather(&mine, 1, MPI_INT, all.counts.data(), 1, MPI_INT, comm);
  std::vector<int> offsets(at(ranks), 0);
  std::vector<int> coordinate_counts(at(ranks));
  std::vector<int> coordinate_offsets(at(ranks), 0);
  for (int r = 0; r < ranks; ++r) {
    if (r > 0) offsets[at(r)] = offsets[at(r - 1)] + all.counts[at(r - 1)];
    coordinate_counts[at(r)] = 3 * all.counts[at(r)];
    coordinate_offsets[at(r)] = 3 * offsets[at(r)];
    for (int k = 0; k < all.counts[at(r)]; ++k) all.rank_of.push_back(r);
  }
  const std::size_t total = all.rank_of.size();
  all.ids.resize(total);
  MPI_Allgatherv(particles.id.data(), mine, MPI_INT64_T, all.ids.data(), all.counts.data(), offsets.data(),
                 MPI_INT64_T, comm);
  std::vector<double> mine_flat;
  for (const auto& x : particles.position) mine_flat.insert(mine_flat.end(), x.data(), x.data() + 3);
  std::vector<double> flat(3 * total);
  MPI_Allgatherv(mine_flat.data(), 3 * mine, MPI_DOUBLE, flat.data(), coordinate_counts.data(),
                 coordinate_offsets.data(), MPI_DOUBLE, comm);
  for (std::size_t k = 0; k < total; ++k) all.positions.emplace_back(flat[3 * k], flat[3 * k + 1], flat[3 * k + 2]);
  return all;
}

// The half-open box [min, max) the decomposition documents.
bool in_box(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& x) {
  return (box.min().array() <= x.array()).all() && (x.array() < box.max().array()).all();
}

// Euclidean distance squared from x to the closed box, written out per axis.
double squared_distance(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& x) {
  double sum = 0.0;
  for (Eigen::Index a = 0; a < 3; ++a) {
    double gap = 0.0;
    if (x[a] < box.min()[a]) gap = box.min()[a] - x[a];
    if (x[a] > box.max()[a]) gap = x[a] - box.max()[a];
    sum += gap * gap;
  }
  return sum;
}

int tree_depth(int ranks) {
  int depth = 0;
  while ((1 << depth) < ranks) ++depth;
  return depth;
}

// Balances the scattered set and migrates; checks ownership, order and the fields.
Particles balanced(DomainDecomposition& decomposition, const std::vector<Eigen::Vector3d>& all) {
  const int rank = decomposition.rank();
  const int ranks = decomposition.rank_count();
  Particles particles = initial_share(all, rank, ranks);
  decomposition.balance(particles.position);
  decomposition.migrate(particles);

  // Kept ones first in their order, then by source rank, each source's in its order.
  std::vector<std::int64_t> expected;
  const auto arriving_from = [&](int source) {
    for (std::size_t g = 0; g < all.size(); ++g) {
      if (first_holder(g, ranks) == source && decomposition.owner(all[g]) == rank) {
        expected.push_back(static_cast<std::int64_t>(g));
      }
    }
  };
  arriving_from(rank);
  for (int source = 0; source < ranks; ++source) {
    if (source != rank) arriving_from(source);
  }
  CHECK(particles.id == expected);
  int wrong = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const std::int64_t id = particles.id[i];
    wrong += particles.position[i] != all[at(id)] || particles.velocity[i] != velocity_of(id) ||
             particles.mass[i] != mass_of(id) || particles.pressure[i] != pressure_of(id);
    wrong += decomposition.owner(particles.position[i]) != rank || !in_box(decomposition.box(rank), particles.position[i]);
  }
  CHECK(wrong == 0);
  return particles;
}

// Every particle once; counts within the documented bound; imbalance() consistent.
void check_ownership_and_balance(const DomainDecomposition& decomposition, const Particles& particles,
                                 std::size_t total, int particles_per_plane) {
  const Everyone all = gather(decomposition.comm(), particles);
  std::vector<std::int64_t> ids = all.ids;
  std::sort(ids.begin(), ids.end());
  std::vector<std::int64_t> every(total);
  std::iota(every.begin(), every.end(), std::int64_t{0});
  CHECK(ids == every);

  const int ranks = decomposition.rank_count();
  const double ideal = static_cast<double>(total) / ranks;
  const double bound = tree_depth(ranks) * (decomposition.cut_tolerance() * static_cast<double>(total) +
                                            0.5 * particles_per_plane + 0.5);
  for (int r = 0; r < ranks; ++r) {
    INFO("rank " << r << " owns " << all.counts[at(r)] << ", ideal " << ideal << ", bound " << bound);
    CHECK(std::abs(all.counts[at(r)] - ideal) <= bound);
  }
  const int largest = *std::max_element(all.counts.begin(), all.counts.end());
  CHECK(decomposition.imbalance(particles.count()) == Approx(largest / ideal).epsilon(1e-14));
}

// The same boxes on every rank; in 2D never cut along z.
void check_boxes(const DomainDecomposition& decomposition) {
  std::vector<double> mine;
  for (int r = 0; r < decomposition.rank_count(); ++r) {
    mine.insert(mine.end(), decomposition.box(r).min().data(), decomposition.box(r).min().data() + 3);
    mine.insert(mine.end(), decomposition.box(r).max().data(), decomposition.box(r).max().data() + 3);
  }
  std::vector<double> roots = mine;
  MPI_Bcast(roots.data(), static_cast<int>(roots.size()), MPI_DOUBLE, 0, decomposition.comm());
  CHECK(mine == roots);
  if (decomposition.dimension() == 2) {
    for (int r = 0; r < decomposition.rank_count(); ++r) {
      CHECK(decomposition.box(r).min().z() == -infinity);
      CHECK(decomposition.box(r).max().z() == infinity);
    }
  }
}

// owner(x) is the one rank whose half-open box holds x: at the probes, and at points
// exactly on every finite box face and corner.
void check_owner_agrees_with_boxes(const DomainDecomposition& decomposition, std::vector<Eigen::Vector3d> probes) {
  const std::size_t base = probes.size();
  for (int r = 0; r < decomposition.rank_count(); ++r) {
    const Eigen::AlignedBox3d& box = decomposition.box(r);
    Eigen::Vector3d corner = probes[at(r) % base];
    for (Eigen::Index a = 0; a < decomposition.dimension(); ++a) {
      for (const double face : {box.min()[a], box.max()[a]}) {
        if (!std::isfinite(face)) continue;
        Eigen::Vector3d x = probes[at(r) % base];
        x[a] = face;
        probes.push_back(x);
        corner[a] = face;
      }
    }
    probes.push_back(corner);
  }
  int wrong = 0;
  for (const auto& x : probes) {
    int holders = 0;
    for (int r = 0; r < decomposition.rank_count(); ++r) {
      if (in_box(decomposition.box(r), x)) {
        ++holders;
        wrong += r != decomposition.owner(x);
      }
    }
    wrong += holders != 1;
  }
  CHECK(wrong == 0);
}

struct Tagged {
  std::int64_t id;
  double value;
  int flag;
};

// The halo against the brute-force set, then exchange() and accumulate() of several
// types. Returns the number of particles, over all ranks, that lie within the radius of
// a box along every axis but farther in Euclidean distance (not ghosts: a ball, not a slab).
int check_halo(const DomainDecomposition& decomposition, const Particles& particles, double radius) {
  const int rank = decomposition.rank();
  const MPI_Comm comm = decomposition.comm();
  Halo halo;
  halo.build(comm, decomposition, particles.position, radius);
  CHECK(halo.owned_count() == particles.count());

  const Everyone all = gather(comm, particles);
  const Eigen::AlignedBox3d& own = decomposition.box(rank);
  std::vector<std::int64_t> expected_ids;
  std::vector<Eigen::Vector3d> expected_positions;
  std::set<int> expected_partners;
  int corner_cases = 0;  // within radius along every axis, but not in Euclidean distance
  for (std::size_t k = 0; k < all.ids.size(); ++k) {
    const int source = all.rank_of[k];
    if (source == rank) continue;
    if (squared_distance(own, all.positions[k]) <= radius * radius) {
      expected_ids.push_back(all.ids[k]);
      expected_positions.push_back(all.positions[k]);
      expected_partners.insert(source);
    } else if ((own.min().array() - radius <= all.positions[k].array()).all() &&
               (all.positions[k].array() <= own.max().array() + radius).all()) {
      ++corner_cases;
    }
  }
  for (const auto& x : particles.position) {
    for (int r = 0; r < decomposition.rank_count(); ++r) {
      if (r != rank && squared_distance(decomposition.box(r), x) <= radius * radius) expected_partners.insert(r);
    }
  }
  CHECK(halo.ghost_count() == static_cast<int>(expected_ids.size()));
  CHECK(halo.partners() == std::vector<int>(expected_partners.begin(), expected_partners.end()));

  const auto owned = particles.size();
  std::vector<std::int64_t> ids = particles.id;
  halo.exchange(ids);
  CHECK(std::vector<std::int64_t>(ids.begin() + static_cast<std::ptrdiff_t>(owned), ids.end()) == expected_ids);
  CHECK(std::equal(particles.id.begin(), particles.id.end(), ids.begin()));

  std::vector<Eigen::Vector3d> positions = particles.position;
  halo.exchange(positions);
  CHECK(std::vector<Eigen::Vector3d>(positions.begin() + static_cast<std::ptrdiff_t>(owned), positions.end()) ==
        expected_positions);

  // A field already sized owned + ghost (stale ghosts) is refilled the same way.
  std::vector<double> scaled(owned);
  for (std::size_t i = 0; i < owned; ++i) scaled[i] = 3.5 * static_cast<double>(particles.id[i]);
  halo.exchange(scaled);
  std::fill(scaled.begin() + static_cast<std::ptrdiff_t>(owned), scaled.end(), -1.0);
  halo.exchange(scaled);
  std::vector<Tagged> tagged(owned);
  for (std::size_t i = 0; i < owned; ++i) tagged[i] = Tagged{particles.id[i], 0.25 * static_cast<double>(i), rank};
  halo.exchange(tagged);
  int wrong = 0;
  for (std::size_t k = 0; k < expected_ids.size(); ++k) {
    const std::size_t slot = owned + k;
    wrong += scaled[slot] != 3.5 * static_cast<double>(expected_ids[k]);
    wrong += tagged[slot].id != expected_ids[k] || tagged[slot].flag == rank;
  }
  CHECK(wrong == 0);

  // accumulate(): each owned particle receives the value of each of its ghost copies.
  std::vector<double> sums(owned, 0.5);
  sums.resize(owned + expected_ids.size());
  std::vector<Eigen::Vector3d> vector_sums(owned, Eigen::Vector3d::Zero());
  vector_sums.resize(sums.size());
  for (std::size_t k = 0; k < expected_ids.size(); ++k) {
    sums[owned + k] = 1.0 + 0.25 * static_cast<double>(expected_ids[k]);
    vector_sums[owned + k] = Eigen::Vector3d(static_cast<double>(expected_ids[k]), 0.5, -2.0);
  }
  halo.accumulate(sums);
  halo.accumulate(vector_sums);
  wrong = 0;
  for (std::size_t i = 0; i < owned; ++i) {
    int copies = 0;
    for (int r = 0; r < decomposition.rank_count(); ++r) {
      copies += r != rank && squared_distance(decomposition.box(r), particles.position[i]) <= radius * radius;
    }
    wrong += sums[i] != 0.5 + copies * (1.0 + 0.25 * static_cast<double>(particles.id[i]));
    wrong += vector_sums[i] != static_cast<double>(copies) * Eigen::Vector3d(static_cast<double>(particles.id[i]), 0.5, -2.0);
  }
  for (std::size_t k = 0; k < expected_ids.size(); ++k) wrong += sums[owned + k] != 1.0 + 0.25 * static_cast<double>(expected_ids[k]);
  CHECK(wrong == 0);

  int corners_everywhere = 0;
  MPI_Allreduce(&corner_cases, &corners_everywhere, 1, MPI_INT, MPI_SUM, comm);
  return corners_everywhere;
}

}  // namespace

TEST_CASE("decomposition: random clouds are balanced and migrated exactly once", "[decomposition]") {
  for (int dimension : {2, 3}) {
    for (double tolerance : {1e-3, 0.0}) {
      INFO(dimension << "D, cut tolerance " << tolerance);
      const auto all = random_cloud(20240611 + static_cast<std::uint64_t>(dimension), 3000, dimension);
      DomainDecomposition decomposition(MPI_COMM_WORLD, dimension, tolerance);
      const Particles particles = balanced(decomposition, all);
      check_ownership_and_balance(decomposition, particles, all.size(), 1);
      check_boxes(decomposition);
      check_owner_agrees_with_boxes(decomposition, random_cloud(99, 500, dimension));
    }
  }
}

TEST_CASE("decomposition: lattices, whose planes cannot be split", "[decomposition]") {
  struct Case {
    int nx, ny, nz;
  };
  // 36 x 20 and 12 x 10 x 8 divide evenly on 1-4 ranks; 7 x 5 x 3 does not.
  for (const Case& c : {Case{36, 20, 1}, Case{12, 10, 8}, Case{7, 5, 3}, Case{9, 13, 1}}) {
    const int dimension = c.nz == 1 ? 2 : 3;
    INFO(c.nx << " x " << c.ny << " x " << c.nz);
    const auto all = lattice(c.nx, c.ny, c.nz);
    const int plane = static_cast<int>(all.size()) / std::min(c.nx, dimension == 3 ? std::min(c.ny, c.nz) : c.ny);
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    const Particles particles = balanced(decomposition, all);
    check_ownership_and_balance(decomposition, particles, all.size(), plane);
    check_boxes(decomposition);
    check_owner_agrees_with_boxes(decomposition, all);
  }
}

TEST_CASE("decomposition: lattices that divide evenly are balanced exactly", "[decomposition]") {
  const auto [rank, ranks] = comm_info(MPI_COMM_WORLD);
  for (const auto& all : {lattice(36, 20, 1), lattice(12, 10, 8)}) {
    const int dimension = all.back().z() == 0.0 ? 2 : 3;
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    const Particles particles = balanced(decomposition, all);
    CHECK(particles.size() * static_cast<std::size_t>(ranks) == all.size());
    CHECK(decomposition.imbalance(particles.count()) == 1.0);
  }
}

TEST_CASE("decomposition: particles exactly on cut planes and corners have one owner", "[decomposition]") {
  const auto [rank, ranks] = comm_info(MPI_COMM_WORLD);
  for (int dimension : {2, 3}) {
    INFO(dimension << "D");
    auto all = random_cloud(7, 800, dimension);
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    Particles particles = initial_share(all, rank, ranks);
    decomposition.balance(particles.position);
    // New particles on every finite face and at the corners of every box; then migrate.
    const std::size_t before = all.size();
    for (int r = 0; r < ranks; ++r) {
      Eigen::Vector3d corner = all[at(r)];
      for (Eigen::Index a = 0; a < dimension; ++a) {
        for (const double face : {decomposition.box(r).min()[a], decomposition.box(r).max()[a]}) {
          if (!std::isfinite(face)) continue;
          Eigen::Vector3d x = all[at(r) + 10];
          x[a] = face;
          all.push_back(x);
          corner[a] = face;
        }
      }
      all.push_back(corner);
    }
    for (std::size_t g = before; g < all.size(); ++g) {
      if (first_holder(g, ranks) != rank) continue;
      const auto id = static_cast<std::int64_t>(g);
      particles.push_back(id, all[g], velocity_of(id), mass_of(id), pressure_of(id));
    }
    decomposition.migrate(particles);
    int outside = 0;
    for (const auto& x : particles.position) outside += !in_box(decomposition.box(rank), x);
    CHECK(outside == 0);
    std::vector<std::int64_t> ids = gather(MPI_COMM_WORLD, particles).ids;
    std::sort(ids.begin(), ids.end());
    std::vector<std::int64_t> every(all.size());
    std::iota(every.begin(), every.end(), std::int64_t{0});
    CHECK(ids == every);
  }
}

TEST_CASE("decomposition: the cuts depend on the particles, not on where they are", "[decomposition]") {
  // Balancing the migrated set again gives the same boxes, bit for bit.
  for (int dimension : {2, 3}) {
    const auto all = random_cloud(31, 2000, dimension);
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    Particles particles = balanced(decomposition, all);
    std::vector<Eigen::AlignedBox3d> first;
    for (int r = 0; r < decomposition.rank_count(); ++r) first.push_back(decomposition.box(r));
    decomposition.balance(particles.position);
    for (int r = 0; r < decomposition.rank_count(); ++r) {
      CHECK(decomposition.box(r).min() == first[at(r)].min());
      CHECK(decomposition.box(r).max() == first[at(r)].max());
    }
    const std::vector<std::int64_t> before = particles.id;
    decomposition.migrate(particles);
    CHECK(particles.id == before);  // nothing moves
  }
}

TEST_CASE("decomposition: few, coincident and far-apart particles", "[decomposition]") {
  const auto [rank, ranks] = comm_info(MPI_COMM_WORLD);
  const std::vector<std::vector<Eigen::Vector3d>> sets{
      {},
      {Eigen::Vector3d(0.5, 0.25, 0.0)},
      {Eigen::Vector3d(0.5, 0.25, 0.0), Eigen::Vector3d(-1.0, 2.0, 0.0), Eigen::Vector3d(3.0, 0.0, 0.0)},
      std::vector<Eigen::Vector3d>(50, Eigen::Vector3d(1.0, 1.0, 0.0)),
      {Eigen::Vector3d(-1e300, 0.0, 0.0), Eigen::Vector3d(1e300, 1.0, 0.0), Eigen::Vector3d(0.0, -1e300, 0.0),
       Eigen::Vector3d(5e-324, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(-5e-324, 1e-300, 0.0)}};
  for (std::size_t s = 0; s < sets.size(); ++s) {
    INFO("set " << s);
    const auto& all = sets[s];
    DomainDecomposition decomposition(MPI_COMM_WORLD, 2, 0.0);
    Particles particles = initial_share(all, rank, ranks);
    decomposition.balance(particles.position);
    decomposition.migrate(particles);
    int wrong = 0;
    for (const auto& x : particles.position) wrong += decomposition.owner(x) != rank;
    CHECK(wrong == 0);
    CHECK(gather(MPI_COMM_WORLD, particles).ids.size() == all.size());
    check_owner_agrees_with_boxes(decomposition, {Eigen::Vector3d(1.0, 1.0, 0.0), Eigen::Vector3d::Zero()});
    Halo halo;
    halo.build(MPI_COMM_WORLD, decomposition, particles.position, 0.5);
    std::vector<std::int64_t> ids = particles.id;
    halo.exchange(ids);
    CHECK(static_cast<int>(ids.size()) == particles.count() + halo.ghost_count());
  }
  // 3 distinct points on 3 ranks: one each.
  if (ranks == 3) {
    DomainDecomposition decomposition(MPI_COMM_WORLD, 2, 0.0);
    Particles particles = initial_share(sets[2], rank, ranks);
    decomposition.balance(particles.position);
    decomposition.migrate(particles);
    CHECK(particles.count() == 1);
  }
}

TEST_CASE("decomposition: before the first balance rank 0 owns all space", "[decomposition]") {
  const auto [rank, ranks] = comm_info(MPI_COMM_WORLD);
  DomainDecomposition decomposition(MPI_COMM_WORLD, 3);
  CHECK(decomposition.owner(Eigen::Vector3d(1e300, -1e300, 0.0)) == 0);
  CHECK(decomposition.box(0).min() == Eigen::Vector3d::Constant(-infinity));
  CHECK(decomposition.box(0).max() == Eigen::Vector3d::Constant(infinity));
  const auto all = random_cloud(3, 200, 3);
  Particles particles = initial_share(all, rank, ranks);
  decomposition.migrate(particles);
  CHECK(particles.size() == (rank == 0 ? all.size() : 0));
  Halo halo;
  halo.build(MPI_COMM_WORLD, decomposition, particles.position, 0.1);
  CHECK(halo.ghost_count() == 0);
}

TEST_CASE("halo: ghosts are every other rank's particle within the radius of the box", "[decomposition]") {
  for (int dimension : {2, 3}) {
    const auto all = random_cloud(20240612 + static_cast<std::uint64_t>(dimension), 3000, dimension);
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    const Particles particles = balanced(decomposition, all);
    int corner_cases = 0;
    for (double radius : {0.07, 0.3, 5.0}) {
      INFO(dimension << "D random, radius " << radius);
      corner_cases += check_halo(decomposition, particles, radius);
    }
    // From 3 ranks on, boxes meet at edges and corners, where ball and slab differ.
    if (decomposition.rank_count() >= 3) CHECK(corner_cases > 0);
  }
  // Lattices with the radius an exact multiple of the spacing: particles exactly at
  // the radius from a box face are ghosts (distance <= radius).
  for (const auto& all : {lattice(40, 24, 1), lattice(14, 12, 10)}) {
    const int dimension = all.back().z() == 0.0 ? 2 : 3;
    DomainDecomposition decomposition(MPI_COMM_WORLD, dimension);
    const Particles particles = balanced(decomposition, all);
    INFO(dimension << "D lattice");
    check_halo(decomposition, particles, 3 * 0.0625);
  }
}

TEST_CASE("decomposition and halo on one rank: no ghosts, migrate is the identity", "[decomposition]") {
  for (int dimension : {2, 3}) {
    const auto all = random_cloud(5, 400, dimension);
    Particles particles = initial_share(all, 0, 1);
    const Particles original = particles;
    DomainDecomposition decomposition(MPI_COMM_SELF, dimension);
    decomposition.balance(particles.position);
    CHECK(decomposition.box(0).min() == Eigen::Vector3d::Constant(-infinity));
    CHECK(decomposition.box(0).max() == Eigen::Vector3d::Constant(infinity));
    decomposition.migrate(particles);
    CHECK(particles.id == original.id);
    CHECK(particles.position == original.position);
    CHECK(particles.velocity == original.velocity);
    CHECK(particles.mass == original.mass);
    CHECK(particles.pressure == original.pressure);
    CHECK(decomposition.imbalance(particles.count()) == 1.0);
    Halo halo;
    halo.build(MPI_COMM_SELF, decomposition, particles.position, 0.2);
    CHECK(halo.ghost_count() == 0);
    CHECK(halo.partners().empty());
    std::vector<double> field(particles.size(), 1.0);
    halo.exchange(field);
    CHECK(field.size() == particles.size());
    halo.accumulate(field);
    CHECK(field == std::vector<double>(particles.size(), 1.0));
  }
}

TEST_CASE("decomposition and halo reject bad input on every rank", "[decomposition]") {
  const auto [rank, ranks] = comm_info(MPI_COMM_WORLD);
  CHECK_THROWS_AS(DomainDecomposition(MPI_COMM_WORLD, 1), std::invalid_argument);
  CHECK_THROWS_AS(DomainDecomposition(MPI_COMM_WORLD, 4), std::invalid_argument);
  CHECK_THROWS_AS(DomainDecomposition(MPI_COMM_WORLD, 3, -0.1), std::invalid_argument);
  CHECK_THROWS_AS(DomainDecomposition(MPI_COMM_WORLD, 3, 1.0), std::invalid_argument);

  // A problem on the last rank only is reported on all of them.
  const bool last = rank == ranks - 1;
  DomainDecomposition planar(MPI_COMM_WORLD, 2);
  std::vector<Eigen::Vector3d> off_plane{Eigen::Vector3d(0.0, 0.0, last ? 1e-9 : 0.0)};
  CHECK_THROWS_AS(planar.balance(off_plane), std::invalid_argument);
  std::vector<Eigen::Vector3d> not_finite{Eigen::Vector3d(last ? std::nan("") : 0.0, 0.0, 0.0)};
  CHECK_THROWS_AS(planar.balance(not_finite), std::invalid_argument);

  const auto all = random_cloud(11, 300, 2);
  const Particles particles = balanced(planar, all);
  Halo halo;
  CHECK_THROWS_AS(halo.build(MPI_COMM_WORLD, planar, particles.position, last ? 0.0 : 0.1), std::invalid_argument);
  CHECK_THROWS_AS(halo.build(MPI_COMM_WORLD, planar, particles.position, std::nan("")), std::invalid_argument);
  if (ranks > 1) {
    // The last rank passes a particle of rank 0's box.
    std::vector<Eigen::Vector3d> foreign = particles.position;
    const auto of_rank_0 = std::find_if(all.begin(), all.end(), [&](const auto& x) { return planar.owner(x) == 0; });
    if (last) foreign.push_back(*of_rank_0);
    CHECK_THROWS_AS(halo.build(MPI_COMM_WORLD, planar, foreign, 0.1), std::invalid_argument);
    CHECK_THROWS_AS(halo.build(MPI_COMM_SELF, planar, particles.position, 0.1), std::invalid_argument);
  }
}
