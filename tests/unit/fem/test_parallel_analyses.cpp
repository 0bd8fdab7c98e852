// The distributed system against a dense serial one built from the same
// element matrices: the partition (1, 2 or 4 ranks) must not change the
// answers beyond round-off. Also the Newmark energy balance on a shell.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fem_solver/analysis/newmark.hpp"
#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "patch_meshes.hpp"

using namespace tankfsi::fem;

namespace {

/// A quarter of a short cylinder clamped at z = 0, symmetric about y = 0.
ShellModel cylinder_model() {
  CylinderPatch c;
  c.radius = 1.0;
  c.length = 1.5;
  c.phi_start = 0.0;
  c.phi_end = 90.0;
  c.divisions_phi = 6;
  c.divisions_z = 5;
  ShellSection s = testing::steel_plate(0.02);
  s.young_modulus = 2e11;
  return ShellModel(cylinder_patch(c), {s});
}

std::vector<DofConstraint> cylinder_supports(const ShellMesh& mesh) {
  std::vector<DofConstraint> out;
  for (const int n : mesh.node_sets.at("z_start"))
    for (int k = 0; k < 6; ++k) out.push_back({n, k, 0.0});
  for (const int n : mesh.node_sets.at("phi_start"))
    for (const int k : {1, 3, 5}) out.push_back({n, k, 0.0});
  // A prescribed (non-zero) rotation exercises the lift of prescribed DOFs.
  out.push_back({mesh.node_sets.at("phi_end").back(), 4, 1e-4});
  return out;
}

LoadSet cylinder_loads(const ShellMesh& mesh) {
  LoadSet loads;
  loads.surfaces.push_back(SurfaceLoad{"shell", 2e5, Eigen::Vector3d(0.0, 1e4, 0.0)});
  loads.points.push_back(PointLoad{mesh.nearest_node(Eigen::Vector3d(1.0, 0.0, 1.5)), Eigen::Vector3d(-1e4, 0, 3e3),
                                   Eigen::Vector3d::Zero()});
  return loads;
}

}  // namespace

TEST_CASE("distributed static solve equals the dense serial solve", "[fem][parallel]") {
  const ShellModel serial_model = cylinder_model();
  const auto constraints = cylinder_supports(serial_model.mesh);
  const LoadSet loads = cylinder_loads(serial_model.mesh);
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), constraints);
  const StaticResult result = solve_static(system, loads);

  // Dense: eliminate the constrained DOFs by hand.
  const Eigen::MatrixXd k = testing::dense_stiffness(serial_model);
  const NodalValues f = nodal_loads(serial_model, loads);
  const auto n = static_cast<std::size_t>(k.rows());
  std::vector<int> free_index(n, 0);
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(k.rows());
  for (const auto& c : constraints) {
    free_index[static_cast<std::size_t>(6 * c.node + c.component)] = -1;
    prescribed(6 * c.node + c.component) = c.value;
  }
  std::vector<Eigen::Index> free;
  for (std::size_t i = 0; i < n; ++i)
    if (free_index[i] == 0) free.push_back(static_cast<Eigen::Index>(i));
  const auto m = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd kff(m, m);
  Eigen::VectorXd rhs(m);
  const Eigen::VectorXd lift = k * prescribed;
  for (Eigen::Index a = 0; a < m; ++a) {
    rhs(a) = f[static_cast<std::size_t>(free[static_cast<std::size_t>(a)])] - lift(free[static_cast<std::size_t>(a)]);
    for (Eigen::Index b = 0; b < m; ++b) kff(a, b) = k(free[static_cast<std::size_t>(a)], free[static_cast<std::size_t>(b)]);
  }
  const Eigen::VectorXd u_free = kff.llt().solve(rhs);
  Eigen::VectorXd u = prescribed;
  for (Eigen::Index a = 0; a < m; ++a) u(free[static_cast<std::size_t>(a)]) = u_free(a);
  const Eigen::Map<const Eigen::VectorXd> distributed(result.displacement.data(), static_cast<Eigen::Index>(n));
  // Both are direct solves of the same SPD system (condition ~1e8): they
  // agree to ~1e-16 x 1e8; 1e-7 relative leaves room and catches any
  // misplaced entry (which would be O(1)).
  CHECK((distributed - u).norm() <= 1e-7 * u.norm());
  // Equilibrium: the support forces (on the supports) equal the applied load
  // less what loads the supported DOFs directly.
  const NodalValues reactions = result.reactions;
  double applied_y = 0.0, supported_y = 0.0;
  for (std::size_t i = 0; i < n; i += 6) {
    applied_y += f[i + 1];
    supported_y += reactions[i + 1] + (free_index[i + 1] == -1 ? f[i + 1] : 0.0);
  }
  CHECK(supported_y == Approx(applied_y).epsilon(1e-9));
}

TEST_CASE("undamped Newmark conserves the energy of a distributed shell", "[fem][parallel][newmark]") {
  const ShellModel model = cylinder_model();
  auto constraints = cylinder_supports(model.mesh);
  constraints.back().value = 0.0;
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), constraints);
  // Released from the static shape under the loads: free vibration.
  const StaticResult start = solve_static(system, cylinder_loads(model.mesh));
  PetscVector u = system.assembler().create_vector();
  PetscVector zero = system.assembler().create_vector();
  system.assembler().scatter(start.displacement, u.get());
  VecSet(zero.get(), 0.0);
  NewmarkIntegrator newmark(system.stiffness(), system.mass(), {},
                            [&system](Mat a) -> std::unique_ptr<LinearSolve> { return system.make_solver(a); });
  newmark.initialise(u.get(), zero.get(), zero.get());
  const double energy = newmark.energy();
  REQUIRE(energy > 0.0);
  for (int n = 0; n < 40; ++n) {
    newmark.step(2e-4, zero.get());
    // Exact for the rule; round-off of 40 direct solves: 1e-10.
    REQUIRE(newmark.energy() == Approx(energy).epsilon(1e-10));
  }
  CHECK(newmark.factorisations() == 1);
}

TEST_CASE("distributed lumped mass sums to the physical mass", "[fem][parallel]") {
  const ShellModel model = cylinder_model();
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), {});
  PetscVector along_x = system.assembler().mass_times_influence(0);
  PetscReal total = 0.0;
  VecSum(along_x.get(), &total);
  CHECK(total == Approx(model.total_mass()).epsilon(1e-12));
  // The shell's area is the polygon's: 6 chords of the quarter circle times the length.
  const double chord = 2.0 * std::sin(std::numbers::pi / 24.0);
  CHECK(model.total_mass() == Approx(7800.0 * 0.02 * 6.0 * chord * 1.5).epsilon(1e-12));
}
