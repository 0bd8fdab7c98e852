// Verlet candidates (neighbour_candidates.hpp, WallCandidates in wall_contacts.hpp):
// the neighbour lists and wall contacts of points moved by up to half the skin (the
// walls: the skin), taken from one search at the points before the move, against a
// search of their own at the moved points — the same pairs with the same distances
// and kernel values, the same contacts bit for bit; a move beyond the skin, or of
// the wall, is refused rather than answered with pairs missing.
#include <catch2/catch.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "sph_solver/isph/wall_contacts.hpp"
#include "sph_solver/neighbours/cell_list.hpp"
#include "sph_solver/neighbours/neighbour_candidates.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "tests/unit/sph/still_tank.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

double uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

Vector3d random_direction(std::mt19937_64& engine, int dimension) {
  Vector3d d(uniform(engine) - 0.5, uniform(engine) - 0.5, dimension == 3 ? uniform(engine) - 0.5 : 0.0);
  return d.normalized();
}

/// Points of a lattice of spacing `spacing` in [0, 1)^d jittered by a tenth of it,
/// and the same points each moved by exactly `move` (the largest move allowed).
std::pair<std::vector<Vector3d>, std::vector<Vector3d>> lattice_and_moved(int dimension, double spacing, double move,
                                                                          std::mt19937_64& engine) {
  std::vector<Vector3d> before;
  std::vector<Vector3d> after;
  const int n = static_cast<int>(1.0 / spacing);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < (dimension == 3 ? n : 1); ++k) {
        Vector3d x = spacing * Vector3d(i, j, k) + 0.1 * spacing * random_direction(engine, dimension);
        if (dimension == 2) x.z() = 0.0;
        before.push_back(x);
        after.push_back(x + move * random_direction(engine, dimension));
      }
  return {before, after};
}

/// Rows as sorted (neighbour, distance, value, slope) tuples.
std::vector<std::vector<std::tuple<int, double, double, double>>> rows_of(const NeighbourList& list) {
  std::vector<std::vector<std::tuple<int, double, double, double>>> rows(static_cast<std::size_t>(list.particle_count()));
  for (int i = 0; i < list.particle_count(); ++i) {
    for (int k = list.offsets[static_cast<std::size_t>(i)]; k < list.offsets[static_cast<std::size_t>(i) + 1]; ++k) {
      const auto e = static_cast<std::size_t>(k);
      rows[static_cast<std::size_t>(i)].emplace_back(list.indices[e], list.distances[e], list.values[e],
                                                     list.slopes[e]);
    }
    std::sort(rows[static_cast<std::size_t>(i)].begin(), rows[static_cast<std::size_t>(i)].end());
  }
  return rows;
}

}  // namespace

TEST_CASE("neighbour candidates: the lists of moved points equal a search of their own", "[neighbours]") {
  std::mt19937_64 engine(7);
  for (const int dimension : {2, 3}) {
    const double spacing = dimension == 2 ? 0.02 : 0.06;
    const Kernel kernel(dimension == 2 ? KernelType::quintic_spline : KernelType::quartic_spline, dimension,
                        1.2 * spacing);
    const double radius = kernel.support_radius();
    const double move = 0.3 * spacing;  // far more than a step moves: many pairs enter and leave
    const auto [before, after] = lattice_and_moved(dimension, spacing, move, engine);
    const int rows = static_cast<int>(before.size()) * 3 / 4;  // the rest stand for ghosts
    const NeighbourCandidates candidates(dimension, before, radius, 2.0 * move * (1.0 + 1e-9), rows);

    CellList cells(dimension);
    for (const auto* points : {&before, &after}) {
      cells.build(*points, radius);
      const auto expected = rows_of(cells.neighbour_list(&kernel, rows));
      const auto found = rows_of(candidates.within_radius(*points, &kernel));
      INFO("dimension " << dimension << (points == &before ? ", before the move" : ", after the move"));
      REQUIRE(found.size() == static_cast<std::size_t>(rows));
      int different_rows = 0;
      for (std::size_t i = 0; i < found.size(); ++i) different_rows += found[i] != expected[i];
      CHECK(different_rows == 0);
    }
    // The move changed the lists: the test is not of points that stayed put.
    cells.build(after, radius);
    const auto moved_rows = rows_of(cells.neighbour_list(&kernel, rows));
    cells.build(before, radius);
    CHECK(moved_rows != rows_of(cells.neighbour_list(&kernel, rows)));
  }
}

TEST_CASE("neighbour candidates refuse points moved beyond half the skin", "[neighbours]") {
  std::mt19937_64 engine(11);
  const auto [before, after] = lattice_and_moved(3, 0.1, 0.05, engine);
  const NeighbourCandidates candidates(3, before, 0.24, 0.099);  // half the skin: 0.0495 < 0.05
  CHECK_THROWS_AS(candidates.within_radius(after, nullptr), std::invalid_argument);
  CHECK_THROWS_AS(candidates.within_radius(std::vector<Vector3d>(before.begin() + 1, before.end()), nullptr),
                  std::invalid_argument);
  CHECK_NOTHROW(candidates.within_radius(before, nullptr));
  CHECK_THROWS_AS(NeighbourCandidates(3, before, 0.24, -1.0), std::invalid_argument);
}

TEST_CASE("wall candidates: the contacts of moved particles equal a search of the index", "[wall_geometry]") {
  FluidModel model = tankfsi::test::water();
  model.dimension = 3;
  model.spacing = 0.05;
  model.smoothing_length = 1.2 * model.spacing;
  const Kernel kernel(KernelType::quartic_spline, 3, model.smoothing_length);
  const WallModel walls(make_cylindrical_tank(0.5, 0.6, 32, 8, 4), model, kernel);
  // Particles inside the tank (and a few just through its wall), moved by up to the skin.
  std::mt19937_64 engine(3);
  std::vector<Vector3d> before;
  std::vector<Vector3d> after;
  const double move = 0.4 * model.spacing;
  for (int i = 0; i < 4000; ++i) {
    const double r = 0.52 * std::sqrt(uniform(engine));
    const double angle = 6.283185307179586 * uniform(engine);
    const Vector3d x(r * std::cos(angle), r * std::sin(angle), 0.6 * uniform(engine) - 0.01);
    before.push_back(x);
    after.push_back(x + move * uniform(engine) * random_direction(engine, 3));
  }
  const WallCandidates candidates = find_wall_candidates(walls, before, move);
  // Kept nearest first, ties by triangle (what find_wall_contacts takes as is at
  // the points searched, and mends where they moved).
  int out_of_order = 0;
  for (std::size_t i = 0; i < before.size(); ++i)
    for (int k = candidates.offsets[i] + 1; k < candidates.offsets[i + 1]; ++k) {
      const WallHit& a = candidates.hits[static_cast<std::size_t>(k - 1)];
      const WallHit& b = candidates.hits[static_cast<std::size_t>(k)];
      out_of_order += a.closest.squared_distance > b.closest.squared_distance ||
                      (a.closest.squared_distance == b.closest.squared_distance && a.triangle >= b.triangle);
    }
  CHECK(out_of_order == 0);
  int contacts = 0;
  for (const auto* points : {&before, &after}) {
    const WallContacts expected = find_wall_contacts(walls, *points, 3);
    const WallContacts found = find_wall_contacts(walls, *points, 3, &candidates);
    REQUIRE(found.offsets == expected.offsets);
    REQUIRE(found.overlap_offsets == expected.overlap_offsets);
    int different = 0;
    for (std::size_t c = 0; c < expected.contacts.size(); ++c) {
      const WallContact& a = expected.contacts[c];
      const WallContact& b = found.contacts[c];
      bool same_feet = a.foot_count == b.foot_count;
      for (int f = 0; same_feet && f < a.foot_count; ++f) {
        const auto& fa = a.feet[static_cast<std::size_t>(f)];
        const auto& fb = b.feet[static_cast<std::size_t>(f)];
        same_feet = fa.triangle == fb.triangle && fa.barycentric == fb.barycentric && fa.weight == fb.weight;
      }
      different += !same_feet || a.normal != b.normal ||
                   a.distance != b.distance || a.values.z0 != b.values.z0 || a.values.z2 != b.values.z2;
    }
    CHECK(different == 0);
    contacts += static_cast<int>(expected.contacts.size());
  }
  CHECK(contacts > 1000);  // most particles near the wall or the floor have one

  // Moved beyond the skin, or the wall moved: refused.
  std::vector<Vector3d> too_far = before;
  too_far[17] += Vector3d(1.01 * move, 0.0, 0.0);
  CHECK_THROWS_AS(find_wall_contacts(walls, too_far, 3, &candidates), std::invalid_argument);
  WallCandidates stale = candidates;
  stale.wall_version += 1;
  CHECK_THROWS_AS(find_wall_contacts(walls, before, 3, &stale), std::invalid_argument);
}
