// Parting of close pairs (close_pairs.hpp): an isolated pair closer than the
// distance ends the distance apart about its midpoint, a lattice is untouched,
// coincident particles part the same way whatever the order of their rows, and a
// particle crowded from all sides moves at most half the distance. In the solver
// (fluid_solver.hpp, 4b): a collapsed pair at the free surface, where the Fickian
// shift is skipped, leaves a step the distance apart and nothing else moves.
#include <catch2/catch.hpp>

#include <mpi.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "sph_solver/isph/close_pairs.hpp"
#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/neighbours/cell_list.hpp"
#include "support/petsc_options_scope.hpp"
#include "tests/unit/sph/still_tank.hpp"

using namespace tankfsi::sph;

namespace {

constexpr double L0 = 0.02;
constexpr double distance = 0.5 * L0;

/// The parting of 2D `points` over their neighbours within 3 L0 (the solver's search).
std::vector<Eigen::Vector3d> parted(const std::vector<Eigen::Vector3d>& points, const std::vector<std::int64_t>& id) {
  CellList cells(2);
  cells.build(points, 3.0 * L0);
  return close_pair_parting(cells.neighbour_list(), points, id, static_cast<int>(points.size()), distance);
}

}  // namespace

TEST_CASE("an isolated close pair ends the distance apart about its midpoint", "[close_pairs]") {
  const Eigen::Vector3d a(0.1, 0.2, 0.0);
  const Eigen::Vector3d b = a + 0.2 * L0 * Eigen::Vector3d(0.6, 0.8, 0.0);
  const auto move = parted({a, b}, {7, 3});
  const Eigen::Vector3d a1 = a + move[0];
  const Eigen::Vector3d b1 = b + move[1];
  CHECK((a1 - b1).norm() == Approx(distance).epsilon(1e-12));
  CHECK(((a1 + b1) / 2 - (a + b) / 2).norm() < 1e-15);
  CHECK(move[0].normalized().dot((a - b).normalized()) == Approx(1.0).epsilon(1e-12));  // along the pair's line
}

TEST_CASE("a lattice of spacing L0 is not moved", "[close_pairs]") {
  std::vector<Eigen::Vector3d> lattice;
  std::vector<std::int64_t> id;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      lattice.emplace_back(i * L0, j * L0, 0.0);
      id.push_back(static_cast<std::int64_t>(id.size()));
    }
  for (const auto& m : parted(lattice, id)) CHECK(m.isZero());
}

TEST_CASE("coincident particles part along x, the lower id to -x, whatever their order", "[close_pairs]") {
  const Eigen::Vector3d p(0.3, 0.1, 0.0);
  const auto forward = parted({p, p}, {4, 9});
  const auto backward = parted({p, p}, {9, 4});
  CHECK(forward[0].isApprox(Eigen::Vector3d(-0.5 * distance, 0.0, 0.0)));
  CHECK(forward[1].isApprox(Eigen::Vector3d(0.5 * distance, 0.0, 0.0)));
  CHECK(backward[0] == forward[1]);
  CHECK(backward[1] == forward[0]);
}

TEST_CASE("a particle crowded from all sides moves at most half the distance", "[close_pairs]") {
  // Three particles 0.1 L0 from the first, all on one side: their pushes add up to
  // 3 x 0.2 L0 = 0.6 L0 along -x, more than the cap of distance / 2 = 0.25 L0.
  const Eigen::Vector3d c(0.2, 0.2, 0.0);
  const double r = 0.1 * L0;
  std::vector<Eigen::Vector3d> points{c, c + Eigen::Vector3d(r, 0, 0), c + r * Eigen::Vector3d(0.8, 0.6, 0),
                                      c + r * Eigen::Vector3d(0.8, -0.6, 0)};
  const auto move = parted(points, {0, 1, 2, 3});
  CHECK(move[0].norm() == Approx(0.5 * distance).epsilon(1e-12));
  CHECK(move[0].x() < 0.0);
  CHECK(std::abs(move[0].y()) < 1e-15);
}

namespace {

/// Every particle's position after one step of the tank with a collapsed pair at
/// the free surface, gathered over the ranks and indexed by id.
std::vector<Eigen::Vector3d> after_one_step(double pair_distance, std::int64_t& first, std::int64_t& second) {
  tankfsi::test::PetscOptionsScope options;
  FluidModel model = tankfsi::test::water();
  model.close_pair_distance = pair_distance;
  const TriangleMesh walls = make_rectangular_tank_2d(0.6, 0.6, 0.2, 0.04);
  Particles particles = tankfsi::test::fill_water(model, walls, 0.2);
  // The filling numbers its particles 0 .. N-1: ids index the gathered positions.
  for (std::size_t i = 0; i < particles.size(); ++i) REQUIRE(particles.id[i] == static_cast<std::int64_t>(i));
  // The top row's particle nearest x = 0.3 and its right-hand neighbour, which is
  // moved to 0.1 L0 from it.
  double top = -1.0;
  for (const auto& x : particles.position) top = std::max(top, x.y());
  std::size_t a = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < particles.position.size(); ++i) {
    const auto& x = particles.position[i];
    if (x.y() > top - 0.1 * L0 && std::abs(x.x() - 0.3) < best) {
      best = std::abs(x.x() - 0.3);
      a = i;
    }
  }
  std::size_t b = a;
  for (std::size_t i = 0; i < particles.position.size(); ++i)
    if ((particles.position[i] - particles.position[a] - Eigen::Vector3d(L0, 0, 0)).norm() < 1e-6 * L0) b = i;
  REQUIRE(b != a);
  particles.position[b] = particles.position[a] + Eigen::Vector3d(0.1 * L0, 0.0, 0.0);
  first = particles.id[a];
  second = particles.id[b];
  const auto count = particles.position.size();

  Eigen::AlignedBox3d domain = walls.bounding_box();
  domain.min().array() -= 2.0;
  domain.max().array() += 2.0;
  FluidSolver solver(MPI_COMM_WORLD, model, walls, particles, domain, "-ppe_ksp_rtol 1e-10");
  solver.step(0.0, 1e-4, Eigen::Vector3d::Zero());
  std::vector<double> flat(3 * count, 0.0);
  const Particles& mine = solver.particles();
  for (int i = 0; i < mine.count(); ++i)
    for (int k = 0; k < 3; ++k)
      flat[3 * static_cast<std::size_t>(mine.id[static_cast<std::size_t>(i)]) + static_cast<std::size_t>(k)] =
          mine.position[static_cast<std::size_t>(i)][k];
  MPI_Allreduce(MPI_IN_PLACE, flat.data(), static_cast<int>(flat.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  std::vector<Eigen::Vector3d> position(count);
  for (std::size_t i = 0; i < count; ++i) position[i] = Eigen::Vector3d(flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]);
  return position;
}

}  // namespace

TEST_CASE("the solver parts a collapsed pair at the free surface and moves nothing else", "[close_pairs]") {
  std::int64_t a = -1;
  std::int64_t b = -1;
  const auto kept = after_one_step(0.0, a, b);
  const auto parted_step = after_one_step(0.5, a, b);
  const auto ia = static_cast<std::size_t>(a);
  const auto ib = static_cast<std::size_t>(b);
  // Without the parting the step leaves the pair collapsed (at the surface the
  // Fickian shift is skipped and the pressure is near zero).
  CHECK((kept[ia] - kept[ib]).norm() < 0.2 * L0);
  CHECK((parted_step[ia] - parted_step[ib]).norm() == Approx(distance).epsilon(1e-9));
  CHECK(((parted_step[ia] + parted_step[ib]) / 2 - (kept[ia] + kept[ib]) / 2).norm() < 1e-12);
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (i == ia || i == ib) continue;
    INFO("particle " << i);
    CHECK((parted_step[i] - kept[i]).norm() < 1e-12);
  }
}
