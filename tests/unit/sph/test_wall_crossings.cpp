// Particles that end a step just behind a wall (wall_crossings.hpp): put back a
// thousandth of L0 in front of the wall they met, without their velocity into it
// relative to the wall; one further behind than L0/2 is left as it is and named
// for the step's crossing check, a path that meets no wall is left alone. In a
// corner both walls hold. In a whole step: a particle a hair above the floor
// moving down at 5 m/s ends the step in front of it, and the step reports it.
#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <mpi.h>

#include <vector>

#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/isph/wall_crossings.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "tests/unit/sph/still_tank.hpp"
#include "tests/unit/sph/two_sided_sheet.hpp"
#include "support/petsc_options_scope.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

/// The 2D tank of the solver checks: floor y = 0, side walls x = 0 and x = 0.6; L0 = 0.02 m.
struct Walls2d {
  FluidModel model = tankfsi::test::water();
  Kernel kernel{model.kernel, 2, model.smoothing_length};
  WallModel walls{make_rectangular_tank_2d(0.6, 0.6, 0.2, 0.04), model, kernel};
};

}  // namespace

TEST_CASE("a particle just past the floor is put back in front of it", "[wall_crossings]") {
  const Walls2d tank;
  const double l0 = tank.model.spacing;
  const std::vector<Vector3d> start{{0.3, 0.01, 0}, {0.2, 0.01, 0}, {0.1, 0.05, 0}};
  std::vector<Vector3d> position{{0.31, -0.1 * l0, 0}, {0.2, -0.6 * l0, 0}, {0.12, 0.04, 0}};
  std::vector<Vector3d> velocity{{2, -3, 0}, {0, -3, 0}, {1, -1, 0}};
  const auto before = position;
  const auto velocity_before = velocity;

  const WallCrossings crossings = return_to_walls(tank.walls, 2, start, position, velocity);
  CHECK(crossings.returned == 1);
  // Put back: on the floor's liquid side by 1e-3 L0, sliding along it.
  CHECK(position[0].x() == Approx(0.31).epsilon(1e-12));
  CHECK(position[0].y() == Approx(1e-3 * l0).epsilon(1e-9));
  CHECK(velocity[0].isApprox(Vector3d(2, 0, 0), 1e-12));
  CHECK(crossed_triangle(tank.walls, start[0], position[0]) == -1);
  // Deeper than L0/2: through the floor, left for the check; no wall met: untouched.
  CHECK(position[1] == before[1]);
  CHECK(velocity[1] == velocity_before[1]);
  REQUIRE(crossings.through.size() == 1);
  CHECK(crossings.through[0].first == 1);
  CHECK(crossings.through[0].second == crossed_triangle(tank.walls, start[1], position[1]));
  CHECK(crossings.through[0].second >= 0);
  CHECK(position[2] == before[2]);
  CHECK(velocity[2] == velocity_before[2]);
}

TEST_CASE("a particle past both walls of a corner is put back inside both", "[wall_crossings]") {
  const Walls2d tank;
  const double l0 = tank.model.spacing;
  const std::vector<Vector3d> start{{0.005, 0.005, 0}};
  std::vector<Vector3d> position{{-0.2 * l0, -0.3 * l0, 0}};
  std::vector<Vector3d> velocity{{-1, -2, 0}};
  CHECK(return_to_walls(tank.walls, 2, start, position, velocity).returned == 1);
  CHECK(position[0].x() == Approx(1e-3 * l0).epsilon(1e-9));
  CHECK(position[0].y() == Approx(1e-3 * l0).epsilon(1e-9));
  CHECK(velocity[0].norm() == 0.0);
}

TEST_CASE("a wall moving into the liquid gives a particle it caught its own normal velocity", "[wall_crossings]") {
  Walls2d tank;
  const double l0 = tank.model.spacing;
  // The whole tank moves up at 1 m/s (positions as they are: the velocities matter here).
  const auto& vertices = tank.walls.mesh().vertices();
  const std::vector<Vector3d> wall_velocity(vertices.size(), Vector3d(0.5, 1.0, 0.0));
  tank.walls.move(std::vector<Vector3d>(vertices.begin(), vertices.end()), wall_velocity);
  const std::vector<Vector3d> start{{0.3, 0.2 * l0, 0}};
  std::vector<Vector3d> position{{0.3, -0.2 * l0, 0}};
  std::vector<Vector3d> velocity{{-1, 0.25, 0}};  // moving up slower than the floor
  CHECK(return_to_walls(tank.walls, 2, start, position, velocity).returned == 1);
  CHECK(velocity[0].isApprox(Vector3d(-1, 1.0, 0), 1e-12));  // the tangential part is the particle's own
}

TEST_CASE("a step that carries a particle a little past the floor puts it back and reports it", "[wall_crossings]") {
  const FluidModel model = tankfsi::test::water();
  const TriangleMesh walls = make_rectangular_tank_2d(0.6, 0.6, 0.2, 0.04);
  Particles particles = tankfsi::test::fill_water(model, walls, 0.2);
  // The particle nearest the floor's middle, a hair above the floor, moving down at
  // 5 m/s: 2.5 mm (0.125 L0) down in the step's first half alone.
  std::size_t chosen = 0;
  for (std::size_t i = 0; i < particles.position.size(); ++i)
    if (std::abs(particles.position[i].x() - 0.3) + particles.position[i].y() <
        std::abs(particles.position[chosen].x() - 0.3) + particles.position[chosen].y())
      chosen = i;
  const std::int64_t id = particles.id[chosen];
  particles.position[chosen].y() = 1e-4;
  particles.velocity[chosen] = Vector3d(0.0, -5.0, 0.0);
  Eigen::AlignedBox3d domain = walls.bounding_box();
  domain.min().array() -= 2.0;
  domain.max().array() += 2.0;
  const tankfsi::test::PetscOptionsScope options;
  FluidSolver solver(MPI_COMM_WORLD, model, walls, particles, domain, "-ppe_ksp_rtol 1e-10");
  const StepReport report = solver.step(0.0, 1e-3, Vector3d::Zero());
  CHECK(report.wall_returned_particles >= 1);
  const Particles& after = solver.particles();
  for (std::size_t i = 0; i < after.position.size(); ++i) {
    CHECK(after.position[i].y() > 0.0);
    if (after.id[i] == id) CHECK(after.velocity[i].y() >= 0.0);
  }
}

TEST_CASE("a particle through a two-sided sheet goes back to the side it came from", "[wall_crossings]") {
  // The sheet at x = 0.3 faces -x; its back (x > 0.3) is liquid too when it is two-sided.
  const FluidModel model = tankfsi::test::water();
  const Kernel kernel(model.kernel, 2, model.smoothing_length);
  WallModel walls(tankfsi::test::vertical_sheet(10), model, kernel);
  walls.replace_mesh(tankfsi::test::vertical_sheet(10), std::vector<char>(walls.mesh().triangle_count(), 1));
  const double l0 = model.spacing;
  const std::vector<Vector3d> start{{0.31, 0.30, 0}, {0.29, 0.20, 0}};
  std::vector<Vector3d> position{{0.3 - 0.2 * l0, 0.30, 0}, {0.3 + 0.2 * l0, 0.21, 0}};
  std::vector<Vector3d> velocity{{-2, 1, 0}, {3, 0.5, 0}};
  const WallCrossings crossings = return_to_walls(walls, 2, start, position, velocity);
  CHECK(crossings.returned == 2);
  CHECK(crossings.through.empty());
  // From behind: back behind (x > 0.3); from the front: back in front.
  CHECK(position[0].x() == Approx(0.3 + 1e-3 * l0).epsilon(1e-12));
  CHECK(velocity[0].isApprox(Vector3d(0, 1, 0), 1e-12));
  CHECK(position[1].x() == Approx(0.3 - 1e-3 * l0).epsilon(1e-12));
  CHECK(velocity[1].isApprox(Vector3d(0, 0.5, 0), 1e-12));
}
