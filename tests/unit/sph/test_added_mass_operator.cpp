// FluidSolver::added_mass_operator against potential flow: a side wall of a
// 2D rectangular tank (width L, liquid depth h, free surface) that starts
// moving into the liquid at unit speed meets the pressure impulse of the
// potential phi with dphi/dx = 1 on the wall, 0 on the far wall and the
// floor, phi = 0 on the surface:
//   phi = sum_n a_n cos(k_n y) cosh(k_n (L - x)),  k_n = (2n - 1) pi / (2h),
// and the impulse on the wall per unit depth, the wall's added mass, is
//   m_a = rho (2/h) sum_n coth(k_n L) / k_n^3
// (0.543 rho h^2 for a wall on an endless reservoir, Westergaard's figure).
// And in 3D: the whole wall of an upright cylinder (radius R, liquid depth H, rigid
// floor, free surface) moving inwards together meets
//   phi = sum_n a_n I0(k_n r) cos(k_n z),  k_n = (n + 1/2) pi / H,
// and its added mass is m_a = 4 pi rho R H^2 sum_n I0(k_n R) / (I1(k_n R) ((n + 1/2) pi)^3).
#include <catch2/catch.hpp>

#include <mpi.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sph_solver/isph/fluid_solver.hpp"
#include "tests/unit/sph/still_tank.hpp"
#include "support/petsc_options_scope.hpp"

using namespace tankfsi::sph;
using tankfsi::test::domain_around;

namespace {

double potential_flow_added_mass(double rho, double width, double depth) {
  double sum = 0.0;
  for (int n = 1; n <= 2000; ++n) {
    const double k = (2.0 * n - 1.0) * std::numbers::pi / (2.0 * depth);
    sum += 1.0 / (std::tanh(k * width) * k * k * k);
  }
  return rho * 2.0 / depth * sum;
}

double potential_flow_breathing_mass(double rho, double radius, double depth) {
  double sum = 0.0;
  for (int n = 0; n < 2000; ++n) {
    const double k = (n + 0.5) * std::numbers::pi / depth;
    sum += std::cyl_bessel_i(0.0, k * radius) / std::cyl_bessel_i(1.0, k * radius) / std::pow((n + 0.5) * std::numbers::pi, 3);
    if (k * radius > 600.0) break;  // I0 / I1 -> 1 and the terms fall as n^-3; beyond here below 1e-9 of the sum
  }
  return 4.0 * std::numbers::pi * rho * radius * depth * depth * sum;
}

/// The tank's wall x = 0 (both rows of its extruded vertices), pushed along +x, into the liquid.
struct SideWall {
  std::vector<int> vertices;
  std::vector<Eigen::Vector3d> normals;
  explicit SideWall(const TriangleMesh& walls) {
    for (std::size_t v = 0; v < walls.vertex_count(); ++v)
      if (std::abs(walls.vertices()[v].x()) < 1e-12) {
        vertices.push_back(static_cast<int>(v));
        normals.emplace_back(1.0, 0.0, 0.0);
      }
  }
};

}  // namespace

TEST_CASE("the added-mass operator of a tank's side wall matches potential flow", "[added_mass]") {
  const tankfsi::test::Tank tank;  // L = 0.6 m, h = 0.4 m, L0 = 0.02 m, at rest
  const FluidModel& model = tank.model;
  const double width = tankfsi::test::width, level = tankfsi::test::level;
  const TriangleMesh& walls = tank.walls.mesh();
  const tankfsi::test::PetscOptionsScope options;
  FluidSolver solver(MPI_COMM_WORLD, model, walls, tank.particles, domain_around(walls), "-ppe_ksp_rtol 1e-10");
  const SideWall side(walls);
  const std::vector<int>& wall = side.vertices;
  REQUIRE(wall.size() >= 4);
  std::vector<double> matrix = solver.added_mass_operator(wall, side.normals);
  MPI_Allreduce(MPI_IN_PLACE, matrix.data(), static_cast<int>(matrix.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const std::size_t n = wall.size();
  double total = 0.0, asymmetry = 0.0, size = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      total += matrix[i * n + j];
      asymmetry = std::max(asymmetry, std::abs(matrix[i * n + j] - matrix[j * n + i]));
      size = std::max(size, std::abs(matrix[i * n + j]));
      CHECK(matrix[i * n + j] >= -1e-9 * size);  // pushing anywhere raises the pressure everywhere
    }
  const double expected = potential_flow_added_mass(model.density, width, level);
  CAPTURE(total, expected, asymmetry / size);
  // L0 = h / 20: measured 88.25 kg/m against 88.34 (-0.1 %); 1 % allows for
  // the rank count's round-off and keeps a wrong factor (the wall's share, a
  // lost free surface, the depth) out by far.
  CHECK(total == Approx(expected).epsilon(0.01));
  // The discrete operator is nearly symmetric (measured 1.7 % of the largest
  // entry: the wall terms' pressure gradient is not the transpose of their
  // Neumann source); the coupling takes its symmetric part.
  CHECK(asymmetry < 0.02 * size);
  // The particles and walls are left as they were: a step afterwards sees a tank at rest.
  const StepReport step = solver.step(0.0, 1e-3, Eigen::Vector3d::Zero());
  CHECK(step.max_speed < 1e-3);
}

// The step's share of a wall velocity jump (set_wall_velocity_jump), which a
// coupling with the operator holds back from the forces it sends: against the
// operator's columns (the same liquid at rest, the same wall, the impulse of
// one PPE solve per vertex), and as the part of the step's wall force that a
// step without the jump does not have (the pressure is linear in the walls'
// velocity, so F(V) - J / dt = F(0)).
TEST_CASE("a wall velocity jump's impulse is the operator's and the step's force less it is the step's without it",
          "[added_mass]") {
  const tankfsi::test::Tank tank;
  const TriangleMesh& walls = tank.walls.mesh();
  const tankfsi::test::PetscOptionsScope options;
  FluidSolver solver(MPI_COMM_WORLD, tank.model, walls, tank.particles, domain_around(walls), "-ppe_ksp_rtol 1e-12");
  const SideWall side(walls);
  const std::vector<int>& wall = side.vertices;
  const std::vector<Eigen::Vector3d>& normals = side.normals;
  std::vector<double> matrix = solver.added_mass_operator(wall, normals);
  MPI_Allreduce(MPI_IN_PLACE, matrix.data(), static_cast<int>(matrix.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const std::size_t n = wall.size();

  // The wall x = 0 starts moving into the liquid at 0.01 m/s (from where it is: the
  // configuration the operator was taken in).
  const double speed = 0.01, dt = 1e-3;
  std::vector<Eigen::Vector3d> velocity(walls.vertex_count(), Eigen::Vector3d::Zero());
  for (const int v : wall) velocity[static_cast<std::size_t>(v)] = Eigen::Vector3d(speed, 0.0, 0.0);
  const std::vector<Eigen::Vector3d> at_rest(walls.vertex_count(), Eigen::Vector3d::Zero());
  const auto summed = [](std::vector<Eigen::Vector3d> values) {
    MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(3 * values.size()), MPI_DOUBLE, MPI_SUM,
                  MPI_COMM_WORLD);
    return values;
  };
  FluidSolver::Checkpoint start;
  solver.save(start);
  solver.move_walls(walls.vertices(), velocity);
  solver.set_wall_velocity_jump(velocity);
  static_cast<void>(solver.step(0.0, dt, Eigen::Vector3d::Zero()));
  REQUIRE(solver.local_jump_impulse().size() == walls.vertex_count());
  const auto jump = summed(solver.local_jump_impulse());
  const auto moving = summed(solver.local_wall_forces());
  solver.restore(start);
  solver.move_walls(walls.vertices(), at_rest);
  static_cast<void>(solver.step(0.0, dt, Eigen::Vector3d::Zero()));
  CHECK(solver.local_jump_impulse().empty());  // used once
  const auto still = summed(solver.local_wall_forces());

  double largest = 0.0, operator_error = 0.0, split_error = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double predicted = 0.0;  // the operator's: -impulse_i . n_i = sum_j A_ij (n_j . V_j)
    for (std::size_t j = 0; j < n; ++j) predicted += matrix[i * n + j] * speed;
    const auto v = static_cast<std::size_t>(wall[i]);
    largest = std::max(largest, std::abs(predicted));
    operator_error = std::max(operator_error, std::abs(-jump[v].dot(normals[i]) - predicted));
  }
  double force_scale = 0.0;
  for (std::size_t v = 0; v < walls.vertex_count(); ++v) {
    force_scale = std::max(force_scale, moving[v].norm());
    split_error = std::max(split_error, (moving[v] - jump[v] / dt - still[v]).norm());
  }
  CAPTURE(largest, operator_error, force_scale, split_error);
  REQUIRE(largest > 0.0);
  // Both are the same linear solve's answer at a relative tolerance of 1e-12
  // (the operator's are per column, the jump's one for all). Measured on 1-4
  // ranks: 2e-12 to 1.6e-11 of the largest entry, and the split 3.8e-8 of the
  // largest force (the full step's solve, with gravity, at that tolerance);
  // a wrong weight, wall or time factor would be off by O(1).
  CHECK(operator_error < 1e-6 * largest);
  CHECK(split_error < 1e-6 * force_scale);
}

TEST_CASE("the added-mass operator of a cylindrical tank's wall matches potential flow", "[added_mass][heavy]") {
  // cases/hydrostatic_3d's tank (R = 0.5 m, 32 facets, dome roof), oil 0.5 m deep,
  // L0 = 0.05 m (10 particles per radius), particles on rings. The wetted wall's
  // vertices (z <= H, the foot ring included) all move inwards at unit speed.
  const tankfsi::test::OilCylinder tank;
  const TriangleMesh& walls = tank.walls;
  const double radius = tank.radius, depth = tank.depth;
  const tankfsi::test::PetscOptionsScope options;
  FluidSolver solver(MPI_COMM_WORLD, tank.model, walls, tank.particles, domain_around(walls), "-ppe_ksp_rtol 1e-10");
  std::vector<int> wall;
  std::vector<Eigen::Vector3d> normals;
  for (std::size_t v = 0; v < walls.vertex_count(); ++v) {
    const Eigen::Vector3d& x = walls.vertices()[v];
    const double r = std::hypot(x.x(), x.y());
    if (std::abs(r - radius) < 1e-9 && x.z() <= depth + 1e-9) {
      wall.push_back(static_cast<int>(v));
      normals.emplace_back(-x.x() / r, -x.y() / r, 0.0);
    }
  }
  REQUIRE(wall.size() == 6 * tankfsi::test::OilCylinder::segments);  // rings at z = 0, 0.1, ..., 0.5
  std::vector<double> matrix = solver.added_mass_operator(wall, normals);
  MPI_Allreduce(MPI_IN_PLACE, matrix.data(), static_cast<int>(matrix.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  double total = 0.0;
  for (const double a : matrix) total += a;
  // The liquid's surface: the top of its highest layer, z = 0.5 m; the wall: the
  // smooth cylinder of radius R its facets approximate (wall_contacts.hpp).
  const double expected = potential_flow_breathing_mass(tank.model.density, radius, depth);
  CAPTURE(total, expected);
  // Measured 577.2 kg against 588.4 (-1.9 %) at the quartic spline's default h = 1.1 L0
  // (since 2026-12-07; kernel.hpp). At h = 1.2 L0:
  // 574.3 kg (-2.4 %; 574.5 kg before the pressure gradient was
  // divided by the particles' own moments, moment_scale()) at 10 particles per radius and depth
  // (2D side wall at 20 per depth: -0.1 %, above), since a curved wall's tables
  // change by the sliver between it and its tangent plane (wall_contacts.hpp);
  // 591.3 kg (+0.5 %) when they were scaled by the area of layers at their
  // representative depths, which overstated Z1 and Z2. At L0 = 0.025 m (20 per
  // radius; an experiment, 29 s): 579.7 kg (-1.5 %), and 587.3 kg (-0.2 %) with
  // the area scaling: both converge, from either side, towards about -0.6 to
  // -0.9 % (first order in L0). With the wall's distance
  // measured to the facets and the rings inside the polygon's apothem: 559.5 kg
  // (-4.9 %); with the smooth wall's distance but those rings (a gap of the
  // sagitta all round): 515.4 kg (-12.4 %); while the free surface took the
  // facets' kernel-sum deficits (2 % at their vertices) for air deep in the liquid:
  // 398.7 kg (-32 %). 3 % holds the first two and fails the others.
  CHECK(total == Approx(expected).epsilon(0.03));
}
