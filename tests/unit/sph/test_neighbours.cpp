// Cell-list neighbour search against brute force O(N^2) search: random clouds in 2D
// and 3D, points exactly at the radius, coincident points, points on cell faces, a
// cloud of two clusters 10^6 radii apart, empty and one-point sets; the cell order
// (a permutation, cells contiguous, Z-order checked with bit-interleaved keys built
// here), the CSR list, apply_permutation and the input checks. Every rank runs every test.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sph_solver/neighbours/cell_list.hpp"
#include "sph_solver/neighbours/permutation.hpp"

using namespace tankfsi::sph;

namespace {

// Uniform in [0, 1) from the top 53 bits of the engine: the same on every platform
// (std:: distributions are implementation-defined).
double uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

std::vector<Eigen::Vector3d> random_cloud(std::mt19937_64& engine, int count, int dimension,
                                          const Eigen::Vector3d& lower, double edge) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    Eigen::Vector3d x(uniform(engine), uniform(engine), dimension == 3 ? uniform(engine) : 0.0);
    points.push_back(lower + edge * x);
  }
  if (dimension == 2) {
    for (auto& x : points) x.z() = 0.0;
  }
  return points;
}

using Visits = std::vector<std::vector<int>>;

// The definition of a neighbour, checked pair by pair.
Visits brute_force(const std::vector<Eigen::Vector3d>& points, double radius) {
  Visits neighbours(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (i != j && (points[i] - points[j]).squaredNorm() < radius * radius) {
        neighbours[i].push_back(static_cast<int>(j));
      }
    }
  }
  return neighbours;
}

// The neighbour list's rows, checking each pair's distance on the way.
Visits searched(const CellList& cells, const std::vector<Eigen::Vector3d>& points) {
  const NeighbourList list = cells.neighbour_list();
  REQUIRE(list.particle_count() == static_cast<int>(points.size()));
  Visits neighbours(points.size());
  int wrong_distance = 0;  // counted, not CHECKed one by one: there are millions of pairs
  for (int i = 0; i < list.particle_count(); ++i) {
    for (int k = list.offsets[static_cast<std::size_t>(i)]; k < list.offsets[static_cast<std::size_t>(i) + 1]; ++k) {
      const int j = list.indices[static_cast<std::size_t>(k)];
      const Eigen::Vector3d x_ij = points[static_cast<std::size_t>(i)] - points[static_cast<std::size_t>(j)];
      wrong_distance += list.distances[static_cast<std::size_t>(k)] != x_ij.norm();
      neighbours[static_cast<std::size_t>(i)].push_back(j);
    }
  }
  CHECK(wrong_distance == 0);
  return neighbours;
}

// Same neighbours as brute force, each visited exactly once.
void check_against_brute_force(const std::vector<Eigen::Vector3d>& points, double radius, int dimension) {
  CellList cells(dimension);
  cells.build(points, radius);
  REQUIRE(cells.point_count() == static_cast<int>(points.size()));
  // Memory follows the points, not the bounding box.
  CHECK(cells.cell_count() <= static_cast<int>(points.size()));
  CHECK(cells.cell_size() >= radius);
  const Visits expected = brute_force(points, radius);
  Visits found = searched(cells, points);
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::sort(found[i].begin(), found[i].end());
    INFO("point " << i);
    CHECK(std::adjacent_find(found[i].begin(), found[i].end()) == found[i].end());  // no repeats
    CHECK(found[i] == expected[i]);
    pairs += expected[i].size();
  }
  INFO("neighbour pairs " << pairs);
}

// Z-order key by interleaving bits (x highest within each level, then y, then z),
// the textbook construction that morton_less must agree with; coordinates < 2^21.
std::uint64_t interleaved_key(const CellCoordinates& cell) {
  std::uint64_t key = 0;
  for (int bit = 20; bit >= 0; --bit) {
    for (std::size_t axis = 0; axis < 3; ++axis) {
      key = (key << 1) | ((static_cast<std::uint64_t>(cell[axis]) >> bit) & 1U);
    }
  }
  return key;
}

}  // namespace

TEST_CASE("cell list matches brute force on random clouds", "[neighbours]") {
  std::mt19937_64 engine(20240611);
  for (int dimension : {2, 3}) {
    for (double radius : {0.031, 0.1, 0.37, 2.0}) {  // from a few to all points within reach
      INFO(dimension << "D, radius " << radius);
      const auto points = random_cloud(engine, 1500, dimension, Eigen::Vector3d(-0.3, 1.7, 0.2), 1.0);
      check_against_brute_force(points, radius, dimension);
    }
  }
}

TEST_CASE("cell list: points at exactly the radius, coincident points, points on cell faces",
          "[neighbours]") {
  // Dyadic numbers, so every distance below is exact in binary: a lattice of spacing =
  // radius puts axis neighbours exactly at the radius (excluded), and the 3-4-5 triples
  // (0.1875, 0.25) and (0.1875, 0, 0.25) lie exactly at 0.3125 = radius (excluded).
  const double radius = 0.3125;
  for (int dimension : {2, 3}) {
    INFO(dimension << "D");
    std::vector<Eigen::Vector3d> points;
    const int z_count = dimension == 3 ? 4 : 1;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        for (int k = 0; k < z_count; ++k) points.emplace_back(radius * i, radius * j, radius * k);
      }
    }
    points.emplace_back(0.1875, 0.25, 0.0);
    points.emplace_back(0.1875, 0.0, dimension == 3 ? 0.25 : 0.0);
    // Coincident points: a pair, and a copy of the lattice point (radius, radius, 0).
    for (int copy = 0; copy < 2; ++copy) points.emplace_back(0.5, 0.5, 0.0);
    points.emplace_back(radius, radius, 0.0);
    // Nearly at the radius, on either side.
    points.emplace_back(radius * 3 + std::nextafter(radius, 0.0), 0.0, 0.0);
    points.emplace_back(radius * 3 + std::nextafter(radius, 1.0), 0.0, 0.0);

    // Points on cell faces: the bounding box is fixed by the points above (corner at the
    // origin), so cells start at multiples of cell_size(); place points exactly there
    // (inside the box, so the rebuild keeps the same cells) and around them.
    CellList probe(dimension);
    probe.build(points, radius);
    const double face = probe.cell_size();
    for (int i = 1; i <= 2; ++i) {
      for (double shift : {-1e-14, 0.0, 1e-14, 0.5 * radius, radius}) {
        points.emplace_back(i * face + shift, 0.4, dimension == 3 ? i * face : 0.0);
        points.emplace_back(0.7, i * face - shift, 0.0);
      }
    }
    check_against_brute_force(points, radius, dimension);

    CellList cells(dimension);
    cells.build(points, radius);
    // Each of the coincident pair sees the other at r = 0.
    const int first_copy = static_cast<int>(dimension == 3 ? 66 : 18);
    REQUIRE(points[static_cast<std::size_t>(first_copy)] == Eigen::Vector3d(0.5, 0.5, 0.0));
    const NeighbourList list = cells.neighbour_list();
    const auto row = list.neighbours_of(first_copy);
    const auto first = list.distances.begin() + list.offsets[static_cast<std::size_t>(first_copy)];
    CHECK(std::count(first, first + static_cast<std::ptrdiff_t>(row.size()), 0.0) == 1);
  }
}

TEST_CASE("cell list: far-apart clusters keep memory small", "[neighbours]") {
  // Two clusters 10^6 radii apart along the diagonal: a dense grid of cells would need
  // ~10^12 (2D) or ~10^18 (3D) cells. The hashed cells number at most the points.
  std::mt19937_64 engine(77);
  const double radius = 0.05;
  for (int dimension : {2, 3}) {
    INFO(dimension << "D");
    const Eigen::Vector3d far = dimension == 3 ? Eigen::Vector3d(1e6 * radius, 1e6 * radius, 1e6 * radius)
                                               : Eigen::Vector3d(1e6 * radius, 1e6 * radius, 0.0);
    auto points = random_cloud(engine, 400, dimension, Eigen::Vector3d::Zero(), 0.5);
    for (const auto& x : random_cloud(engine, 400, dimension, far, 0.5)) points.push_back(x);
    check_against_brute_force(points, radius, dimension);
  }
}

TEST_CASE("cell list: empty and single-point sets", "[neighbours]") {
  for (int dimension : {2, 3}) {
    CellList cells(dimension);
    cells.build(std::vector<Eigen::Vector3d>{}, 0.1);
    CHECK(cells.point_count() == 0);
    CHECK(cells.cell_count() == 0);
    CHECK(cells.cell_order().empty());
    const NeighbourList empty = cells.neighbour_list();
    CHECK(empty.offsets == std::vector<int>{0});
    CHECK(empty.indices.empty());

    const std::vector<Eigen::Vector3d> one{Eigen::Vector3d(3.0, -4.0, 0.0)};
    cells.build(one, 0.1);
    CHECK(cells.point_count() == 1);
    CHECK(cells.cell_count() == 1);
    CHECK(cells.cell_order() == std::vector<int>{0});
    const NeighbourList single = cells.neighbour_list();
    CHECK(single.offsets == std::vector<int>{0, 0});
  }
}

TEST_CASE("cell list is rebuilt from scratch", "[neighbours]") {
  std::mt19937_64 engine(5);
  const auto first = random_cloud(engine, 600, 3, Eigen::Vector3d::Zero(), 1.0);
  const auto second = random_cloud(engine, 300, 3, Eigen::Vector3d(10.0, 0.0, -4.0), 2.0);
  CellList reused(3);
  reused.build(first, 0.2);
  reused.build(second, 0.3);
  CellList fresh(3);
  fresh.build(second, 0.3);
  CHECK(reused.cell_order() == fresh.cell_order());
  const NeighbourList a = reused.neighbour_list();
  const NeighbourList b = fresh.neighbour_list();
  CHECK(a.offsets == b.offsets);
  CHECK(a.indices == b.indices);
}

TEST_CASE("cell list: the neighbours' indices alone are the neighbour list's rows", "[neighbours]") {
  std::mt19937_64 engine(11);
  for (int dimension : {2, 3}) {
    INFO(dimension << "D");
    const auto points = random_cloud(engine, 2000, dimension, Eigen::Vector3d::Zero(), 1.0);
    CellList cells(dimension);
    cells.build(points, 0.09);
    for (int rows : {-1, 0, 1, 1500}) {
      INFO(rows << " rows");
      const NeighbourList full = cells.neighbour_list(nullptr, rows);
      const NeighbourList indices = cells.neighbour_indices(rows);
      CHECK(indices.offsets == full.offsets);
      CHECK(indices.indices == full.indices);
      CHECK(indices.distances.empty());
      CHECK(full.distances.size() == full.indices.size());
    }
    CHECK_THROWS_AS(cells.neighbour_indices(2001), std::invalid_argument);
  }
}

TEST_CASE("cell order: a permutation grouping cells contiguously in Z-order", "[neighbours]") {
  std::mt19937_64 engine(1234);
  for (int dimension : {2, 3}) {
    INFO(dimension << "D");
    const double radius = 0.06;
    const auto points = random_cloud(engine, 3000, dimension, Eigen::Vector3d(2.0, -1.0, 0.5), 1.0);
    CellList cells(dimension);
    cells.build(points, radius);
    const std::vector<int>& order = cells.cell_order();
    REQUIRE(order.size() == points.size());
    CHECK(is_permutation(order));

    // Each point lies in the cell it is filed under (cells counted from the box corner).
    Eigen::Vector3d lower = points.front();
    for (const auto& x : points) lower = lower.cwiseMin(x);
    for (int i = 0; i < static_cast<int>(points.size()); ++i) {
      const CellCoordinates cell = cells.cell_of(i);
      for (int axis = 0; axis < dimension; ++axis) {
        const double offset = points[static_cast<std::size_t>(i)][axis] - lower[axis];
        CHECK(offset >= static_cast<double>(cell[static_cast<std::size_t>(axis)]) * cells.cell_size());
        CHECK(offset < static_cast<double>(cell[static_cast<std::size_t>(axis)] + 1) * cells.cell_size());
      }
      if (dimension == 2) CHECK(cell[2] == 0);
    }

    // Along the order: a cell, once left, never comes back; keys never decrease; within
    // a cell the points keep their index order.
    std::set<CellCoordinates> finished;
    for (std::size_t k = 1; k < order.size(); ++k) {
      const CellCoordinates previous = cells.cell_of(order[k - 1]);
      const CellCoordinates current = cells.cell_of(order[k]);
      if (current != previous) {
        CHECK(finished.insert(previous).second);
        CHECK(finished.count(current) == 0);
        CHECK(interleaved_key(previous) < interleaved_key(current));
      } else {
        CHECK(order[k - 1] < order[k]);
      }
    }
    CHECK(static_cast<int>(finished.size()) + 1 == cells.cell_count());
  }
}

TEST_CASE("morton_less agrees with interleaved keys", "[neighbours]") {
  std::mt19937_64 engine(99);
  for (int trial = 0; trial < 20000; ++trial) {
    CellCoordinates a{}, b{};
    // Small ranges make ties and shared prefixes frequent.
    const std::uint64_t range = trial % 2 == 0 ? 8 : (1U << 21);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      a[axis] = static_cast<std::int64_t>(engine() % range);
      b[axis] = static_cast<std::int64_t>(engine() % range);
    }
    CHECK(morton_less(a, b) == (interleaved_key(a) < interleaved_key(b)));
  }
}

TEST_CASE("neighbour list (CSR): each row in cell order", "[neighbours]") {
  std::mt19937_64 engine(42);
  for (int dimension : {2, 3}) {
    const auto points = random_cloud(engine, 1000, dimension, Eigen::Vector3d::Zero(), 1.0);
    CellList cells(dimension);
    cells.build(points, 0.09);
    const NeighbourList list = cells.neighbour_list();
    REQUIRE(list.particle_count() == static_cast<int>(points.size()));
    CHECK(list.offsets.front() == 0);
    CHECK(list.offsets.back() == static_cast<int>(list.indices.size()));
    CHECK(list.distances.size() == list.indices.size());
    std::vector<int> place(points.size());  // where each point comes in cell order
    for (std::size_t k = 0; k < points.size(); ++k)
      place[static_cast<std::size_t>(cells.cell_order()[k])] = static_cast<int>(k);
    int out_of_order = 0;
    for (int i = 0; i < list.particle_count(); ++i) {
      const auto row = list.neighbours_of(i);
      for (std::size_t k = 1; k < row.size(); ++k)
        out_of_order += place[static_cast<std::size_t>(row[k - 1])] >= place[static_cast<std::size_t>(row[k])];
    }
    CHECK(out_of_order == 0);
  }
}

TEST_CASE("apply_permutation reorders any per-particle array", "[neighbours]") {
  const std::vector<double> values{10.0, 11.0, 12.0, 13.0};
  const std::vector<int> order{2, 0, 3, 1};
  CHECK(apply_permutation(values, order) == std::vector<double>{12.0, 10.0, 13.0, 11.0});
  const std::vector<Eigen::Vector3d> vectors{Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                             Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Ones()};
  const auto moved = apply_permutation(vectors, order);
  CHECK(moved[0] == Eigen::Vector3d::UnitZ());
  CHECK(moved[3] == Eigen::Vector3d::UnitY());
  CHECK_THROWS_AS(apply_permutation(values, std::vector<int>{0, 1, 2}), std::invalid_argument);
  CHECK_THROWS_AS(apply_permutation(values, std::vector<int>{0, 1, 1, 3}), std::invalid_argument);
  CHECK_THROWS_AS(apply_permutation(values, std::vector<int>{0, 1, 2, 4}), std::invalid_argument);
  CHECK(apply_permutation(std::vector<int>{}, std::vector<int>{}).empty());
}

TEST_CASE("cell list rejects bad input", "[neighbours]") {
  CHECK_THROWS_AS(CellList(1), std::invalid_argument);
  CHECK_THROWS_AS(CellList(4), std::invalid_argument);
  CellList planar(2);
  const std::vector<Eigen::Vector3d> in_plane{Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.0, 0.0, 0.0)};
  CHECK_THROWS_AS(planar.build(in_plane, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(planar.build(in_plane, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(planar.build(in_plane, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(planar.build(std::vector<Eigen::Vector3d>{Eigen::Vector3d(0.0, 0.0, 1e-9)}, 0.1),
                  std::invalid_argument);
  CHECK_THROWS_AS(planar.build(std::vector<Eigen::Vector3d>{Eigen::Vector3d(std::nan(""), 0.0, 0.0)}, 0.1),
                  std::invalid_argument);
  CellList spatial(3);
  CHECK_THROWS_AS(
      spatial.build(std::vector<Eigen::Vector3d>{Eigen::Vector3d::Zero(), Eigen::Vector3d(1e300, 0.0, 0.0)}, 0.1),
      std::invalid_argument);
}
