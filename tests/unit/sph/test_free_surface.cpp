// The free surface as air beyond a plane (free_surface.hpp) on the still tank's
// lattice, against the geometry and the hydrostatic pressure rho g (level - y):
//  - the distance and normal read from each particle's density deficit are those of
//    the plane y = level (the top of the highest layer);
//  - with the air in the PPE, the hydrostatic pressure solves it up to the surface
//    (no Dirichlet particle: the top layer comes out at rho g L0/2);
//  - with the air in the pressure gradient, every layer under the surface is in
//    equilibrium, where the bare symmetric sum holds the top layer with 91 % of its
//    weight and pushes the second with 108 %;
//  - the air's forces on the liquid sum to zero, so the walls carry the whole weight.
// And in a 3D box: the corners of three walls and the vertical edges at the surface
// (two walls and the air) hold their particles as the rest of the liquid; a deficit
// deep in the liquid (a curved wall's) is not taken for a surface, so the PPE of a
// cylindrical tank at rest gives the hydrostatic pressure.
// Particles within a kernel support of the side walls are left out of the checks
// (the corner of air and wall is counted twice: free_surface.hpp).
#include <catch2/catch.hpp>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/isph/free_surface.hpp"
#include "sph_solver/isph/particle_terms.hpp"
#include "sph_solver/isph/pressure_poisson.hpp"
#include "sph_solver/walls/primitive_meshes.hpp"
#include "still_tank.hpp"
#include "support/petsc_options_scope.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;
using namespace tankfsi::test;

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Depth of particle i below the surface plane, in layers of L0 (0.5 for the top layer).
double depth_in_layers(const Tank& tank, int i) {
  return (level - tank.particles.position[at(i)].y()) / tank.model.spacing;
}

struct AirTank : Tank {
  std::vector<SurfaceContact> air = surface_contacts(view(), particles.mass, density, walls);
  std::vector<double> completed = completed_density(density, air, model.density * walls.table().lattice_share(), model.density);
};

/// Water at rest in a 0.3 x 0.3 m box of 12 triangles, 0.2 m deep (L0 = 0.02 m,
/// quartic spline, h = 1.2 L0, 2,250 particles) with the hydrostatic pressure and its air.
struct WaterBox3d {
  static constexpr double side = 0.3;
  static constexpr double depth = 0.2;
  FluidModel model = [] {
    FluidModel m = water();
    m.dimension = 3;
    m.kernel = KernelType::quartic_spline;
    return m;
  }();
  TriangleMesh box = make_box(Vector3d::Zero(), Vector3d(side, side, 0.3), NormalSide::inward);
  Particles particles = fill_water(model, box, depth);
  StillLiquid3d liquid{model, box, particles};
};

/// The PPE of the liquid at rest (v* = g dt, the walls' Neumann share the only
/// source), solved to 1e-12: the worst |P - rho g (depth - z)| in rho g L0.
double worst_hydrostatic_ppe_error(const StillLiquid3d& liquid, double depth) {
  const int n = liquid.particles.count();
  const double dt = 1e-3;
  const Vector3d v_star(0.0, 0.0, -g * dt);
  std::vector<double> source(at(n));
  for (int i = 0; i < n; ++i) source[at(i)] = -wall_laplacian_share(liquid.view(), i, v_star, v_star / dt, dt);
  std::vector<std::int64_t> index(at(n));
  for (int i = 0; i < n; ++i) index[at(i)] = i;
  std::vector<double> pressure(at(n), 0.0);
  const PetscOptionsScope options;
  PressurePoisson ppe(MPI_COMM_SELF, "-ppe_ksp_rtol 1e-12");
  ppe.solve(liquid.view(), liquid.particles.mass, liquid.completed, index, std::vector<unsigned char>(at(n), 0), source,
            pressure);
  const double unit = liquid.model.density * g * liquid.model.spacing;
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const double exact = liquid.model.density * g * (depth - liquid.particles.position[at(i)].z());
    worst = std::max(worst, std::abs(pressure[at(i)] - exact) / unit);
  }
  return worst;
}

}  // namespace

TEST_CASE("the air beyond a flat surface is found at its plane", "[free_surface]") {
  const AirTank tank;
  int top = 0, second = 0;
  for (int i = 0; i < tank.particles.count(); ++i) {
    if (tank.near_side(i)) continue;
    const SurfaceContact& c = tank.air[at(i)];
    const double depth = depth_in_layers(tank, i);
    if (depth > 2.0) {
      // A surface farther than 2 L0 is not looked for (the bulk's density noise).
      REQUIRE_FALSE(c.active);
      continue;
    }
    REQUIRE(c.active);
    // 1e-3 L0: the table's interpolation error of Z0 (1.5e-5 of Z0(0)) over its slope.
    CHECK(c.distance / tank.model.spacing == Approx(depth).margin(1e-3));
    CHECK((c.normal - Vector3d(0.0, -1.0, 0.0)).norm() < 1e-9);
    // Completed by the air and read against the lattice (completed_density()): rho0.
    CHECK(tank.completed[at(i)] == tank.model.density);
    (depth < 1.0 ? top : second) += 1;
  }
  CHECK(top > 20);
  CHECK(second > 20);
}

TEST_CASE("a deficit deep in the liquid that no first layer confirms is not a surface", "[free_surface]") {
  // A curved, faceted wall measured by its facets completed its particles' kernel
  // sums only to 0.5-2 % (the cylinder of cases/hydrostatic_3d: -2.1 % at its
  // vertices; -0.15 to +0.28 % since the distance is the smooth wall's). Read as a surface,
  // such a deficit put the air 1.4-1.9 L0 from particles half a metre deep, and its
  // Dirichlet share pulled the PPE's pressure 18 % below rho g (H - z) (measured on
  // that cylinder). Here every particle from the third layer down misses 2 %.
  AirTank tank;
  std::vector<double> density = tank.density;
  for (int i = 0; i < tank.particles.count(); ++i)
    if (depth_in_layers(tank, i) > 2.0) density[at(i)] *= 0.98;
  const auto air = surface_contacts(tank.view(), tank.particles.mass, density, tank.walls);
  int deep = 0, surface = 0;
  for (int i = 0; i < tank.particles.count(); ++i) {
    if (tank.near_side(i)) continue;
    INFO("particle at depth " << depth_in_layers(tank, i) << " layers");
    if (depth_in_layers(tank, i) > 2.0) {
      // Without the check the 2 % put a surface 1.5 L0 away (2D quintic spline).
      CHECK_FALSE(air[at(i)].active);
      ++deep;
    } else {
      // The two layers under the real surface keep their air as before.
      REQUIRE(air[at(i)].active);
      CHECK(air[at(i)].distance == tank.air[at(i)].distance);
      ++surface;
    }
  }
  CHECK(deep > 100);
  CHECK(surface > 40);
}

TEST_CASE("with the air the hydrostatic pressure solves the PPE up to the surface", "[free_surface]") {
  const AirTank tank;
  const auto view = tank.view(tank.air);
  const int n = tank.particles.count();
  // At rest: v* = -g dt e_y, no divergence, no density error; the walls' Neumann
  // share rho0 g is the whole right-hand side (as in FluidSolver::step).
  const double dt = 1e-3;
  const Vector3d v_star(0.0, -g * dt, 0.0);
  std::vector<double> source(at(n), 0.0);
  for (int i = 0; i < n; ++i) source[at(i)] = -wall_laplacian_share(view, i, v_star, v_star / dt, dt);
  std::vector<std::int64_t> index(at(n));
  for (int i = 0; i < n; ++i) index[at(i)] = i;
  std::vector<double> pressure(at(n), 0.0);
  const std::vector<unsigned char> no_dirichlet(at(n), 0);
  const PetscOptionsScope options;
  PressurePoisson ppe(MPI_COMM_SELF, "-ppe_ksp_rtol 1e-12");
  ppe.solve(view, tank.particles.mass, tank.completed, index, no_dirichlet, source, pressure);
  double worst_top = 0.0, worst_below = 0.0, worst_side = 0.0;
  for (int i = 0; i < n; ++i) {
    const double exact = tank.model.density * g * (level - tank.particles.position[at(i)].y());
    const double error = std::abs(pressure[at(i)] - exact) / (tank.model.density * g * tank.model.spacing);
    double& worst = tank.near_side(i) ? worst_side : depth_in_layers(tank, i) < 1.0 ? worst_top : worst_below;
    worst = std::max(worst, error);
  }
  INFO("worst |P - rho g (level - y)| / (rho g L0): top layer " << worst_top << ", below " << worst_below
                                                                << ", beside the side walls " << worst_side);
  // 1e-2 rho g L0 (2 Pa; 2 % of the top layer's 98 Pa, 0.05 % of the floor's 3900 Pa):
  // the corners where walls and air overlap (counted twice, see free_surface.hpp)
  // perturb the solution everywhere a little; on a periodic lattice the error is 1e-5.
  CHECK(worst_top < 1e-2);
  CHECK(worst_below < 1e-2);
  CHECK(worst_side < 1e-2);
}

TEST_CASE("with the air every layer under the surface is in equilibrium", "[free_surface]") {
  const AirTank tank;
  const double dt = 1e-3;
  const std::vector<Vector3d> v_star(tank.particles.size(), Vector3d(0.0, -g * dt, 0.0));
  const std::vector<Vector3d> a_star(tank.particles.size(), Vector3d(0.0, -g, 0.0));
  std::vector<Vector3d> bare_force(tank.walls.mesh().vertex_count(), Vector3d::Zero());
  std::vector<Vector3d> wall_force = bare_force;
  const auto bare = pressure_acceleration(tank.view(), tank.particles.mass, tank.completed, tank.particles.pressure,
                                          v_star, a_star, dt, bare_force);
  const auto with_air = pressure_acceleration(tank.view(tank.air), tank.particles.mass, tank.completed,
                                              tank.particles.pressure, v_star, a_star, dt, wall_force);
  double worst_surface = 0.0, worst_side = 0.0, worst_elsewhere = 0.0, bare_top = 0.0, bare_second = 0.0;
  double weight = 0.0;
  int top = 0, second = 0;
  for (int i = 0; i < tank.particles.count(); ++i) {
    weight += tank.particles.mass[at(i)] * g;
    const double residual = (with_air[at(i)] + Vector3d(0.0, -g, 0.0)).norm() / g;
    const double depth = depth_in_layers(tank, i);
    double& worst = tank.near_side(i) ? worst_side : depth < 3.0 ? worst_surface : worst_elsewhere;
    worst = std::max(worst, residual);
    if (tank.near_side(i)) continue;
    if (depth < 1.0) {
      bare_top += bare[at(i)].y() / g;
      ++top;
    } else if (depth < 2.0) {
      bare_second += bare[at(i)].y() / g;
      ++second;
    }
  }
  INFO("worst |a_p + g| / g with the air: top three layers " << worst_surface << ", beside the side walls (corners "
       "and contact lines included) " << worst_side << ", elsewhere " << worst_elsewhere
       << "; bare symmetric sum: top layer " << bare_top / top << " g, second " << bare_second / second << " g");
  // 3e-3 at the surface: the third layer (air share 1e-4 at 2.5 L0, not looked for)
  // is left with 2.7e-3 (2.1e-3 until the pressure gradient was divided by the
  // lattice's moment, 0.99938 here: the lattice's own -6e-4 offset part of it);
  // 1.2e-3 elsewhere: the floor layer is left with 1.0e-3 (table interpolation;
  // 1.6e-3 with the lattice's offset). Without the air the top and second layers
  // are off by 9 % and 8 % (checked, so the test sees them), without the corner
  // overlaps the corner particle by 8 g.
  CHECK(worst_surface < 3e-3);
  CHECK(worst_side < 3e-3);
  CHECK(worst_elsewhere < 1.2e-3);
  CHECK(bare_top / top == Approx(0.91).margin(0.01));
  CHECK(bare_second / second == Approx(1.08).margin(0.01));
  // The walls carry the liquid's weight: the air's forces on the liquid sum to
  // (nearly) zero. 1e-3: the lattice's quadrature error of the bulk (6e-4).
  Vector3d total = Vector3d::Zero();
  for (const Vector3d& f : wall_force) total += f;
  INFO("wall force " << total.transpose() << " N/m against the weight " << weight);
  CHECK(-total.y() == Approx(weight).epsilon(1e-3));
  CHECK(std::abs(total.x()) < 1e-9 * weight);
}

TEST_CASE("a drop alone in the air falls freely: air all round, no pressure", "[free_surface]") {
  // Water at rest in the still tank's walls (filled to 0.2 m) and one drop 0.25 m
  // above it, moving at (0.5, -1) m/s: nothing within its support but the air, so
  // the air's PPE diagonal alone fixes its pressure at 0 and the step moves it
  // ballistically. (Without that diagonal its PPE row was empty: the pressure was
  // whatever the solver made of 0 P = the density-error source, -4e6 Pa in an
  // overflow run, and the next step blew up.)
  const FluidModel model = water();
  const TriangleMesh walls = make_rectangular_tank_2d(width, 0.6, 0.2, 0.04);
  Particles particles = fill_water(model, walls, 0.2);
  const std::int64_t drop = particles.count();
  const Vector3d x0(0.31, 0.45, 0.0), v0(0.5, -1.0, 0.0);
  particles.push_back(drop, x0, v0, model.density * model.spacing * model.spacing, 0.0);
  Eigen::AlignedBox3d domain = walls.bounding_box();
  domain.min().array() -= 1.0;
  domain.max().array() += 1.0;
  FluidSolver solver(MPI_COMM_WORLD, model, walls, particles, domain, "-ppe_ksp_rtol 1e-12");
  const double dt = 1e-3;
  solver.step(0.0, dt, Vector3d::Zero());
  int found = 0;
  const Particles& now = solver.particles();
  for (int i = 0; i < now.count(); ++i) {
    if (now.id[at(i)] != drop) continue;
    ++found;
    CHECK(now.pressure[at(i)] == Approx(0.0).margin(1e-9));
    const Vector3d v1 = v0 + dt * Vector3d(0.0, -model.gravity, 0.0);
    CHECK((now.velocity[at(i)] - v1).norm() < 1e-12);
    CHECK((now.position[at(i)] - (x0 + 0.5 * dt * (v0 + v1))).norm() < 1e-12);
  }
  int total = 0;
  MPI_Allreduce(&found, &total, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  CHECK(total == 1);
}

TEST_CASE("a 3D box at rest: corners of three walls and edges at the surface in equilibrium", "[free_surface]") {
  // WaterBox3d with the hydrostatic pressure: every particle's pressure
  // acceleration must balance gravity. Measured worst |a_p + g| / g:
  // the floor's corners 5.1e-5, the vertical edges at the surface 3.2e-5, the side
  // walls 9.7e-5, elsewhere 9.4e-5 (the tables' interpolation). Before the pressure
  // gradient was divided by the lattice's moment (1.0043; wall_kernel_table.hpp):
  // 1.19e-2, 7.5e-3, 7.3e-3 and 4.3e-3. With the old fallback bound of the
  // renormalised gradient the corners had 0.30 (they fell back to the bare sum);
  // without the octant of two walls and the air the edges at the surface had
  // 5.4e-2, their surface 0.446 L0 away instead of 0.5 L0. 3e-4 holds the first
  // and fails the others.
  const WaterBox3d water_box;
  const auto& [model, box, particles, liquid] = water_box;
  const double side = WaterBox3d::side, depth = WaterBox3d::depth;
  const auto& air = liquid.air;
  const int n = particles.count();
  const double dt = 1e-3;
  const std::vector<Vector3d> v_star(particles.size(), Vector3d(0.0, 0.0, -g * dt));
  const std::vector<Vector3d> a_star(particles.size(), Vector3d(0.0, 0.0, -g));
  std::vector<Vector3d> wall_force(box.vertex_count(), Vector3d::Zero());
  const auto acceleration = pressure_acceleration(liquid.view(), particles.mass, liquid.completed, particles.pressure,
                                                  v_star, a_star, dt, wall_force);
  const double l0 = model.spacing;
  double worst = 0.0;
  int corners = 0, top_edges = 0;
  for (int i = 0; i < n; ++i) {
    const Vector3d& x = particles.position[at(i)];
    const double residual = (acceleration[at(i)] + Vector3d(0.0, 0.0, -g)).norm() / g;
    INFO("particle at " << x.transpose() << ": a = " << acceleration[at(i)].transpose());
    CHECK(residual < 3e-4);
    worst = std::max(worst, residual);
    const bool on_edge = std::min(x.x(), side - x.x()) < l0 && std::min(x.y(), side - x.y()) < l0;
    corners += on_edge && x.z() < l0;
    if (on_edge && x.z() > depth - l0) {
      // The surface plane z = depth is half a layer above the top edge particle.
      CHECK(air[at(i)].distance / l0 == Approx(0.5).margin(1e-3));
      ++top_edges;
    }
  }
  INFO("worst |a_p + g| / g " << worst);
  CHECK(corners == 4);
  CHECK(top_edges == 4);
  // And the hydrostatic pressure solves the PPE there (as in 2D above; measured
  // worst 3e-4 rho g L0, the tolerance the 2D tank's 1e-2).
  CHECK(worst_hydrostatic_ppe_error(liquid, depth) < 1e-2);
}

TEST_CASE("at a contact line the walls stop an approach along their normals only", "[free_surface]") {
  // WaterBox3d's liquid moving as a whole towards the wall x = 0 at 0.1 m/s,
  // no pressure and no body force: what acts is the walls' Neumann condition against
  // the approach, rho0 (v^n - v_wall)·n / dt. A wall's half-space is symmetric along
  // the wall; the air's overlap with it (a contact line, and the octant of two walls
  // and the air at a vertical edge) keeps that part (contact_line_wall_gradient()), so
  // no particle there is pushed up or down. Measured 0 exactly; when the copy taken
  // out of the overlap carried the approach too, the top layer at the contact line
  // was pushed up with 0.40 times its push off the wall (0.65 at a vertical edge),
  // the second layer with 0.032.
  const WaterBox3d water_box;
  const auto& [model, box, particles, liquid] = water_box;
  const int n = particles.count();
  const double dt = 1e-3;
  const std::vector<Vector3d> v_star(particles.size(), Vector3d(-0.1, 0.0, 0.0));
  const std::vector<Vector3d> a_star(particles.size(), Vector3d::Zero());
  const std::vector<double> no_pressure(particles.size(), 0.0);
  std::vector<Vector3d> wall_force(box.vertex_count(), Vector3d::Zero());
  const auto acceleration =
      pressure_acceleration(liquid.view(), particles.mass, liquid.completed, no_pressure, v_star, a_star, dt, wall_force);
  int contact_line = 0;
  for (int i = 0; i < n; ++i) {
    const Vector3d& x = particles.position[at(i)];
    if (liquid.air[at(i)].overlap_count == 0 || x.x() > 2.0 * model.spacing) continue;
    ++contact_line;
    INFO("particle at " << x.transpose() << ": a = " << acceleration[at(i)].transpose());
    CHECK(acceleration[at(i)].x() > 0.0);
    CHECK(std::abs(acceleration[at(i)].z()) < 1e-12 * acceleration[at(i)].x());
  }
  CHECK(contact_line >= 30);
}

TEST_CASE("with the Wendland kernel the PPE gives the hydrostatic pressure in a 3D box", "[free_surface]") {
  // cases/hydrostatic_3d/box.yaml's oil with Wendland C2 at h = 1.5 L0, whose
  // lattice sum is 1.0031 (the quartic spline's 1.00002): the sums' volumes m / rho
  // are read against the lattice (completed_density()), so that a lattice's are
  // L0^3, as in the wall tables. Measured worst |P - rho g (H - z)| 0.0029 rho g L0;
  // with the raw kernel sums 0.031 (checked by reverting). Tolerance 0.01.
  FluidModel model = oil_3d();
  model.kernel = KernelType::wendland_c2;
  model.smoothing_length = 1.5 * model.spacing;
  const double depth = 0.5;
  const TriangleMesh box = make_box(Vector3d::Zero(), Vector3d(1.0, 1.0, 0.6), NormalSide::inward);
  const Particles particles = fill_water(model, box, depth);
  const StillLiquid3d liquid(model, box, particles);
  const double worst = worst_hydrostatic_ppe_error(liquid, depth);
  INFO("worst |P - rho g (H - z)| / (rho g L0) " << worst);
  CHECK(worst < 0.01);
}

TEST_CASE("a cylindrical tank at rest: the PPE gives the hydrostatic pressure", "[free_surface]") {
  // cases/hydrostatic_3d: oil 0.5 m deep in a tank of R = 0.5 m (32 wall facets, dome
  // roof), L0 = 0.05 m, particles on rings. With the facets' distance the outer rings'
  // kernel sums missed up to 2.1 % (the facets' vertices); taken for a surface 1.4-1.9
  // L0 away they put the PPE's pressure up to 2.8 rho g L0 below rho g (H - z) (rms
  // 1.5; measured). With the first-layer check: worst 0.13, rms 0.019 rho g L0; with
  // the smooth wall's distance (sums -0.15 to +0.28 %) worst 0.13; at the quartic
  // spline's default h = 1.1 L0 since (kernel.hpp) 0.15. Tolerance 0.25.
  const OilCylinder tank;
  const StillLiquid3d liquid(tank.model, tank.walls, tank.particles);
  const double worst = worst_hydrostatic_ppe_error(liquid, OilCylinder::depth);
  INFO("worst |P - rho g (H - z)| / (rho g L0) " << worst);
  CHECK(worst < 0.25);
}
