// The volume probe (fluid_probes.hpp, liquid_volume): the liquid inside a box and
// outside it, against the count of lattice particles on either side, on any
// number of ranks (every rank gets the same sums).
#include <catch2/catch.hpp>

#include <mpi.h>

#include "sph_solver/isph/fluid_probes.hpp"
#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "tests/unit/sph/still_tank.hpp"

using namespace tankfsi::sph;

TEST_CASE("volume probe: the liquid inside a box and outside it", "[probes]") {
  // 0.6 m wide tank filled to 0.2 m at L0 = 0.02 m: 30 x 10 particles of
  // 4e-4 m^2 each (per metre of depth), the lattice offset L0/2 from the walls.
  const FluidModel model = tankfsi::test::water();
  const TriangleMesh walls = make_rectangular_tank_2d(0.6, 0.6, 0.2, 0.04);
  const Particles particles = tankfsi::test::fill_water(model, walls, 0.2);
  Eigen::AlignedBox3d domain = walls.bounding_box();
  domain.min().array() -= 1.0;
  domain.max().array() += 1.0;
  const FluidSolver solver(MPI_COMM_WORLD, model, walls, particles, domain, "");
  const double cell = model.spacing * model.spacing;

  // The left third (x < 0.2: 10 columns) and the lowest 4 layers (y < 0.08).
  const Eigen::AlignedBox3d left(Eigen::Vector3d(-0.1, -0.1, -1.0), Eigen::Vector3d(0.2, 0.08, 1.0));
  const auto volume = liquid_volume(solver, left);
  CHECK(volume[0] == Approx(40 * cell).epsilon(1e-12));
  CHECK(volume[1] == Approx(260 * cell).epsilon(1e-12));

  // A box holding the whole liquid leaves nothing outside; one beside it, nothing inside.
  const auto all = liquid_volume(solver, Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d(0.6, 0.6, 1)));
  CHECK(all[0] == Approx(0.6 * 0.2).epsilon(1e-12));
  CHECK(all[1] == 0.0);
  const auto none = liquid_volume(solver, Eigen::AlignedBox3d(Eigen::Vector3d(1, 0, -1), Eigen::Vector3d(2, 1, 1)));
  CHECK(none[0] == 0.0);
  CHECK(none[1] == Approx(0.6 * 0.2).epsilon(1e-12));
}
