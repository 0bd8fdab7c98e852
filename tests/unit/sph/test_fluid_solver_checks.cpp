// The fluid solver's end-of-step checks (FluidSolver::check_state): a particle
// whose path in a step goes through a wall, or a non-finite field, stops the run
// with the step, the time and the first such particle, the same message on every
// rank; a tank at rest passes them.
#include <catch2/catch.hpp>

#include <mpi.h>

#include <cmath>
#include <limits>
#include <string>

#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/particles/filling.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "tests/unit/sph/still_tank.hpp"
#include "support/petsc_options_scope.hpp"

using namespace tankfsi::sph;
using Catch::Matchers::Contains;

namespace {

struct SolverTank {
  tankfsi::test::PetscOptionsScope options;  // the solvers' options, this test's alone
  FluidModel model = tankfsi::test::water();
  TriangleMesh walls = make_rectangular_tank_2d(0.6, 0.6, 0.2, 0.04);
  Particles particles;
  std::int64_t floor_particle = -1;  ///< the one nearest the floor's middle

  SolverTank() {
    particles = tankfsi::test::fill_water(model, walls, 0.2);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < particles.count(); ++i) {
      const auto& x = particles.position[static_cast<std::size_t>(i)];
      const double d = std::abs(x.x() - 0.3) + x.y();
      if (d < best) {
        best = d;
        floor_particle = particles.id[static_cast<std::size_t>(i)];
      }
    }
  }

  FluidSolver solver() const {
    Eigen::AlignedBox3d domain = walls.bounding_box();
    domain.min().array() -= 2.0;
    domain.max().array() += 2.0;
    return FluidSolver(MPI_COMM_WORLD, model, walls, particles, domain, "-ppe_ksp_rtol 1e-10");
  }
};

std::string step_error(FluidSolver& solver, double dt) {
  try {
    solver.step(0.0, dt, Eigen::Vector3d::Zero());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a tank at rest passes the end-of-step checks", "[fluid_checks]") {
  const SolverTank tank;
  auto solver = tank.solver();
  CHECK(step_error(solver, 1e-3).empty());
}

TEST_CASE("a particle driven through the floor in one step stops the run", "[fluid_checks]") {
  SolverTank tank;
  for (int i = 0; i < tank.particles.count(); ++i)
    if (tank.particles.id[static_cast<std::size_t>(i)] == tank.floor_particle)
      tank.particles.velocity[static_cast<std::size_t>(i)] = Eigen::Vector3d(0.0, -2000.0, 0.0);
  auto solver = tank.solver();
  const std::string error = step_error(solver, 1e-3);  // 2 m in the step: through the floor at y = 0
  CHECK_THAT(error, Contains("step 1 at t = 0 s: "));
  CHECK_THAT(error, Contains("crossed a wall; the first, id " + std::to_string(tank.floor_particle) + ", went from ("));
  CHECK_THAT(error, Contains("the step is too long for the liquid's speed or the wall's motion"));
}

TEST_CASE("a non-finite velocity stops the run with the particle", "[fluid_checks]") {
  SolverTank tank;
  tank.particles.velocity[0] = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  auto solver = tank.solver();
  const std::string error = step_error(solver, 1e-3);
  INFO(error);
  CHECK_THAT(error, Contains("step 1 at t = 0 s: "));
  CHECK_THAT(error, Contains("non-finite"));
}
