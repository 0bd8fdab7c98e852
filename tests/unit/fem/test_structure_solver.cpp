// The API the coupling calls: external nodal loads on the interface every
// step, Newmark advance, interface displacement and velocity getters; and
// the ground-motion load -M iota a_g.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "common/excitation/ground_motion.hpp"
#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/analysis/structure_solver.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "patch_meshes.hpp"

using namespace tankfsi::fem;

namespace {

/// A half cylinder clamped at z = 0 whose whole surface is the interface.
ShellModel half_cylinder() {
  CylinderPatch c;
  c.radius = 1.0;
  c.length = 2.0;
  c.phi_start = 0.0;
  c.phi_end = 180.0;
  c.divisions_phi = 8;
  c.divisions_z = 6;
  ShellSection s = testing::steel_plate(0.01);
  s.young_modulus = 2e11;
  ShellMesh mesh = cylinder_patch(c);
  std::vector<int> all(mesh.elements.size());
  for (std::size_t e = 0; e < all.size(); ++e) all[e] = static_cast<int>(e);
  mesh.element_sets["wetted"] = all;
  return ShellModel(std::move(mesh), {s});
}

std::vector<DofConstraint> clamp(const ShellMesh& mesh) {
  std::vector<DofConstraint> out;
  for (const int n : mesh.node_sets.at("z_start"))
    for (int k = 0; k < 6; ++k) out.push_back({n, k, 0.0});
  return out;
}

/// A harmonic ground motion along (1, 0.5, 0.2).
class TestMotion final : public tankfsi::GroundMotion {
 public:
  [[nodiscard]] Eigen::Vector3d acceleration(double t) const override {
    return std::sin(60.0 * t) * Eigen::Vector3d(1.0, 0.5, 0.2);
  }
  [[nodiscard]] double duration() const override { return 1.0; }
};

double largest_difference(const NodalValues& a, const NodalValues& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

double largest(const NodalValues& a) { return largest_difference(a, NodalValues(a.size(), 0.0)); }

}  // namespace

TEST_CASE("external interface loads act as the same loads given as a load case", "[fem][coupling-api]") {
  const ShellModel model = half_cylinder();
  LoadSet pressure;
  pressure.surfaces.push_back(SurfaceLoad{"shell", 5e4, Eigen::Vector3d::Zero()});
  const tankfsi::ZeroGroundMotion still;
  const RayleighCoefficients damping{2.0, 1e-5};

  StructureSystem with_case(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver reference(with_case, damping, pressure, still);

  StructureSystem with_api(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver coupled(with_api, damping, LoadSet{}, still);
  coupled.set_interface(extract_interface(with_api.model().mesh, "wetted"));
  // What the fluid side would send: the consistent nodal forces of the
  // pressure at the interface vertices, reset before every step. The
  // reference starts in balance with its loads at t = 0: so does this one.
  const NodalValues nodal = nodal_loads(model, pressure);
  std::vector<double> forces;
  for (const int node : coupled.interface().node_ids)
    for (std::size_t k = 0; k < 3; ++k) forces.push_back(nodal[6 * static_cast<std::size_t>(node) + k]);
  coupled.set_external_loads(forces);
  coupled.balance_acceleration();
  for (int step = 0; step < 20; ++step) {
    coupled.set_external_loads(forces);
    coupled.advance(1e-4);
    reference.advance(1e-4);
  }
  // Same equations, same factorisation: equal to round-off of the response.
  // The velocity is Newmark's difference of displacements over the step, so
  // their round-off (1e-12, from MUMPS summing in another order on several
  // ranks) reaches it magnified by |u| / (|v| dt): 1e-10 of the velocity.
  REQUIRE(largest(reference.displacement()) > 0.0);
  CHECK(largest_difference(coupled.displacement(), reference.displacement()) <= 1e-12 * largest(reference.displacement()));
  CHECK(largest_difference(coupled.velocity(), reference.velocity()) <= 1e-10 * largest(reference.velocity()));
  // The getters return the interface vertices' values, 3 each.
  const auto u = coupled.interface_displacements();
  const auto v = coupled.interface_velocities();
  REQUIRE(u.size() == 3 * coupled.interface().node_ids.size());
  REQUIRE(v.size() == u.size());
  for (std::size_t i = 0; i < coupled.interface().node_ids.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      CHECK(u[3 * i + k] == coupled.displacement()[6 * static_cast<std::size_t>(coupled.interface().node_ids[i]) + k]);
      CHECK(v[3 * i + k] == coupled.velocity()[6 * static_cast<std::size_t>(coupled.interface().node_ids[i]) + k]);
    }
  CHECK(coupled.total_external_force().isApprox(reference.total_external_force(), 1e-12));
  CHECK(coupled.steps() == 20);
  CHECK(coupled.time() == Approx(2e-3));
  CHECK_THROWS_AS(coupled.set_external_loads(std::vector<double>(5, 0.0)), std::invalid_argument);
}

TEST_CASE("ground acceleration loads the structure with -M iota a_g", "[fem][coupling-api]") {
  // The ground motion through the solver against the same inertial forces
  // -m_i a_g(t) given as external loads at every node (the whole structure is
  // the interface): equal histories. a_g(0) = 0: both start in balance.
  const ShellModel model = half_cylinder();
  const TestMotion motion;
  const tankfsi::ZeroGroundMotion still;
  StructureSystem shaken_system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver shaken(shaken_system, {}, LoadSet{}, motion);
  StructureSystem pushed_system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver pushed(pushed_system, {}, LoadSet{}, still);
  pushed.set_interface(extract_interface(pushed_system.model().mesh, "wetted"));
  const auto& mass = pushed_system.assembler().nodal_mass();
  const double dt = 2e-4;
  for (int step = 1; step <= 30; ++step) {
    // advance(dt) holds the external loads over the step and applies the
    // ground's at the step's end, t + dt.
    const Eigen::Vector3d a = motion.acceleration(step * dt);
    std::vector<double> forces;
    for (const int node : pushed.interface().node_ids)
      for (int k = 0; k < 3; ++k) forces.push_back(-mass[6 * static_cast<std::size_t>(node) + static_cast<std::size_t>(k)] * a(k));
    pushed.set_external_loads(forces);
    pushed.advance(dt);
    shaken.advance(dt);
  }
  REQUIRE(largest(shaken.displacement()) > 0.0);
  CHECK(largest_difference(shaken.displacement(), pushed.displacement()) <= 1e-10 * largest(shaken.displacement()));
}

TEST_CASE("a failed step leaves the last good state; the largest displacement needs no gather", "[fem][coupling-api]") {
  const ShellModel model = half_cylinder();
  const tankfsi::ZeroGroundMotion still;
  StructureSystem system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver solver(system, {2.0, 1e-5}, LoadSet{}, still);
  solver.set_interface(extract_interface(system.model().mesh, "wetted"));
  std::vector<double> forces(3 * solver.interface().node_ids.size(), 0.0);
  for (std::size_t i = 0; i < forces.size(); i += 3) forces[i] = 10.0;
  solver.set_external_loads(forces);
  for (int step = 0; step < 5; ++step) solver.advance(1e-4);
  const NodalValues u = solver.displacement();
  const NodalValues v = solver.velocity();
  // Against the gathered state: the largest |(u_x, u_y, u_z)| of any node.
  double largest_gathered = 0.0;
  for (std::size_t i = 0; i < u.size(); i += 6)
    largest_gathered = std::max(largest_gathered, std::sqrt(u[i] * u[i] + u[i + 1] * u[i + 1] + u[i + 2] * u[i + 2]));
  REQUIRE(largest_gathered > 0.0);
  CHECK(solver.largest_displacement() == Approx(largest_gathered).epsilon(1e-14));

  // A load that poisons the solve, on the last interface vertex (at the free end; the
  // first ones are clamped, and a load on a support never reaches the solve).
  forces[forces.size() - 3] = std::numeric_limits<double>::quiet_NaN();
  solver.set_external_loads(forces);
  CHECK_THROWS_WITH(solver.advance(1e-4), Catch::Matchers::Contains("structure step 6") &&
                                              Catch::Matchers::Contains("non-finite displacement"));
  CHECK(solver.steps() == 5);
  CHECK(solver.time() == Approx(5e-4));
  const bool same_displacement = solver.displacement() == u;  // bit for bit: nothing of the failed step was kept
  const bool same_velocity = solver.velocity() == v;
  CHECK(same_displacement);
  CHECK(same_velocity);
}

// Implicit coupling repeats a window from a checkpoint: after restore() the
// same loads give the same states as the first pass did: bit for bit on one
// rank; on several, MUMPS may sum its messages in another order from one solve
// to the next, so to round-off of the response (1e-12).
TEST_CASE("a restored checkpoint repeats the steps exactly", "[fem][coupling-api]") {
  const ShellModel model = half_cylinder();
  const tankfsi::ZeroGroundMotion still;
  StructureSystem system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver solver(system, RayleighCoefficients{2.0, 1e-5}, LoadSet{}, still);
  solver.set_interface(extract_interface(system.model().mesh, "wetted"));
  const std::size_t n = solver.interface().node_ids.size();
  const auto loads_at = [&](int step) {
    std::vector<double> f(3 * n);
    for (std::size_t i = 0; i < f.size(); ++i) f[i] = 100.0 * std::sin(0.3 * static_cast<double>(i) + 0.2 * step);
    return f;
  };
  for (int step = 0; step < 5; ++step) {
    solver.set_external_loads(loads_at(step));
    solver.advance(1e-4);
  }
  StructureSolver::Checkpoint checkpoint;
  solver.save(checkpoint);
  const auto run_window = [&] {
    for (int step = 5; step < 10; ++step) {
      solver.set_external_loads(loads_at(step));
      solver.advance(1e-4);
    }
    return std::make_pair(solver.displacement(), solver.velocity());
  };
  const auto first = run_window();
  // A different pass in between (another load), then back to the checkpoint.
  solver.restore(checkpoint);
  solver.set_external_loads(std::vector<double>(3 * n, 5e3));
  solver.advance(1e-4);
  solver.restore(checkpoint);
  CHECK(solver.time() == Approx(5e-4));
  CHECK(solver.steps() == 5);
  const auto again = run_window();
  REQUIRE(largest(first.first) > 0.0);
  CHECK(largest_difference(first.first, again.first) <= 1e-12 * largest(first.first));
  CHECK(largest_difference(first.second, again.second) <= 1e-12 * largest(first.second));
}

TEST_CASE("a structure started in equilibrium with its loads stays there: the static solution, at rest",
          "[fem][coupling-api]") {
  const ShellModel model = half_cylinder();
  LoadSet pressure;
  pressure.surfaces.push_back(SurfaceLoad{"shell", 5e4, Eigen::Vector3d::Zero()});
  const tankfsi::ZeroGroundMotion still;
  StructureSystem system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  StructureSolver solver(system, RayleighCoefficients{2.0, 1e-5}, pressure, still);
  solver.start_at_equilibrium();
  const NodalValues initial = solver.displacement();
  StructureSystem static_system(MPI_COMM_WORLD, half_cylinder(), clamp(model.mesh));
  const NodalValues expected = solve_static(static_system, pressure).displacement;
  // The same linear system solved twice: equal to the solver's round-off.
  CHECK(largest_difference(initial, expected) <= 1e-10 * largest(expected));
  CHECK(largest(solver.velocity()) == 0.0);
  for (int k = 0; k < 20; ++k) solver.advance(1e-4);
  // Newmark leaves a balanced state alone (up to the round-off of F - K u).
  CHECK(largest_difference(solver.displacement(), expected) <= 1e-9 * largest(expected));
  CHECK(largest(solver.velocity()) <= 1e-9 * largest(expected) / 1e-4);
}
