// The liquid next to a curved wall at rest, one step after the filling: the wall's
// pressure term must hold it where it was laid. cases/hydrostatic_3d's cylinder
// (tankfsi::test::OilCylinder: R = 0.5 m, 32 facets, oil 0.5 m deep, L0 = 0.05 m,
// rings), one step of 2 ms from the hydrostatic pressure; the radial acceleration
// (v_r / dt) of the ring next to the wall, between its floor ring and the two
// surface layers, and its vertical acceleration against the next ring's, layer by
// layer (the first step lifts the whole liquid a little, more near the surface:
// 0.02-0.16 g, the filled rings' density errors; the wall's own share must not
// add to it).
#include <catch2/catch.hpp>

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "sph_solver/isph/fluid_solver.hpp"
#include "support/petsc_options_scope.hpp"
#include "tests/unit/sph/still_tank.hpp"

using namespace tankfsi::sph;

TEST_CASE("a cylinder at rest: the ring next to the curved wall stays in balance at the first step", "[wall_contacts]") {
  // Scaling the wall tables by the area of layers at their representative depths
  // (before the sliver, wall_contacts.hpp) made Z1 4 % too strong at this radius
  // (10 L0): the ring was pushed inwards, its mean a_r -0.185 g, the largest
  // |a_r| 0.32 g (measured by reverting). With the sliver: mean +0.0195 g,
  // largest 0.062 g, on 1 to 4 ranks alike. The rings are not a lattice (their
  // kernel sums within 0.3 % of the lattice's away from the axis; the box's lattice
  // moves off by 2e-4 g at most),
  // so the bounds are the measured values' with a margin: 0.05 g on the ring's
  // mean, 0.1 g on any particle, both well below the area scaling's.
  const tankfsi::test::OilCylinder tank;
  const tankfsi::test::PetscOptionsScope options;
  FluidSolver solver(MPI_COMM_WORLD, tank.model, tank.walls, tank.particles, tankfsi::test::domain_around(tank.walls),
                     "-ppe_ksp_rtol 1e-10");
  const double dt = 2e-3;
  static_cast<void>(solver.step(0.0, dt, Eigen::Vector3d::Zero()));
  const Particles& p = solver.particles();
  const double spacing = tank.model.spacing;
  double largest = 0.0, sum = 0.0;
  int count = 0;
  // Per ring (0: next to the wall, 1: the next) the sum of a_z / g and the count.
  std::array<double, 2> lift{};
  std::array<int, 2> in_ring{};
  for (int i = 0; i < p.count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d& x = p.position[k];
    const double r = std::hypot(x.x(), x.y());
    if (r < tank.radius - 2.0 * spacing || x.z() < 1.5 * spacing || x.z() > tank.depth - 2.0 * spacing) continue;
    const std::size_t ring = r < tank.radius - spacing ? 1 : 0;
    lift[ring] += p.velocity[k].z() / dt / tank.model.gravity;
    ++in_ring[ring];
    if (ring == 1) continue;
    const double radial = (p.velocity[k].x() * x.x() + p.velocity[k].y() * x.y()) / r / dt / tank.model.gravity;
    largest = std::max(largest, std::abs(radial));
    sum += radial;
    ++count;
  }
  MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &count, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, lift.data(), 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, in_ring.data(), 2, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  const double extra_lift = lift[0] / in_ring[0] - lift[1] / in_ring[1];
  INFO("ring next to the wall: " << count << " particles, mean a_r " << sum / count << " g, largest |a_r| " << largest
                                 << " g; mean a_z " << lift[0] / in_ring[0] << " g against the next ring's "
                                 << lift[1] / in_ring[1] << " g");
  REQUIRE(count == 60 * 7);  // 60 a layer, layers at z = 0.075 ... 0.375 m
  REQUIRE(in_ring[1] > 0);
  CHECK(std::abs(sum / count) < 0.05);
  CHECK(largest < 0.1);
  // The sliver's tangential moment bent alike along the axis and around it (H C3
  // both ways, not the cylinder's H C3 / 2 along it: wall_contacts.hpp) lifted the
  // ring next to the wall 0.016 g more than the next one (0.011-0.030 g in each
  // layer), and in a damped run drove a steady roll up the wall; with the
  // shape's deviator 0.0006 g (measured, 1 to 4 ranks alike). Since the pressure
  // gradient is divided by the particles' own moments (moment_scale()): -0.0001 g
  // with the deviator, 1 to 4 ranks alike; +0.015 g with it switched off
  // (measured by a temporary change). At the quartic spline's default h = 1.1 L0
  // (since 2026-12-07; kernel.hpp, at h = 1.2 L0 before): -0.0006 g, the ring's
  // mean a_r +0.038 g and its largest 0.089 g (+0.0195 and 0.062 g at 1.2 L0: the
  // narrower kernel reads the rings' arrangement with fewer neighbours). Bound 0.005 g.
  CHECK(std::abs(extra_lift) < 0.005);
}
