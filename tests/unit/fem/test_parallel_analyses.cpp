// The distributed system against a dense serial one built from the same
// element matrices: the partition (1, 2 or 4 ranks) must not change the
// answers beyond round-off. Also the Newmark energy balance on a shell, the
// iterative option (CG + GAMG), the support totals (base shear, overturning
// moment) and the modes against a dense eigensolution.
#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "fem_solver/analysis/modal_analysis.hpp"
#include "fem_solver/analysis/newmark.hpp"
#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/app/structure_output.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "patch_meshes.hpp"
#include "support/petsc_options_scope.hpp"

using namespace tankfsi;
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

TEST_CASE("CG with smoothed aggregation (GAMG) and the rigid-body near-null space solves as MUMPS does", "[fem][parallel]") {
  const ShellModel model = cylinder_model();
  auto constraints = cylinder_supports(model.mesh);
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), constraints);
  const StaticResult direct = solve_static(system, cylinder_loads(model.mesh));
  REQUIRE(direct.solver == "preonly/cholesky(mumps)");
  // The options -shell_ksp_type cg -shell_pc_type gamg (from the command line
  // or structure.solver_options), in this test's own options database.
  StaticResult iterative;
  {
    const tankfsi::test::PetscOptionsScope options;
    PetscOptionsSetValue(nullptr, "-shell_ksp_type", "cg");
    PetscOptionsSetValue(nullptr, "-shell_pc_type", "gamg");
    iterative = solve_static(system, cylinder_loads(model.mesh));
  }
  CHECK(iterative.solver == "cg/gamg");
  CHECK(iterative.iterations > 0);
  // The six rigid-body modes that GAMG's aggregates represent keep CG to a
  // few hundred iterations on this thin (t/R = 0.02) shell.
  CHECK(iterative.iterations < 500);
  // CG stops at 1e-10 of the preconditioned residual: the error is that times
  // the condition number (~1e6 here), far below 1e-3 of the answer.
  double difference = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < direct.displacement.size(); ++i) {
    difference = std::max(difference, std::abs(iterative.displacement[i] - direct.displacement[i]));
    largest = std::max(largest, std::abs(direct.displacement[i]));
  }
  CHECK(difference <= 1e-3 * largest);
  INFO("GAMG: " << iterative.iterations << " iterations, largest difference " << difference / largest);
}

TEST_CASE("base shear and overturning moment are the load's force and moment about the base", "[fem][parallel]") {
  // The quarter cylinder clamped at z = 0 and held on y = 0, loaded by a
  // force at the top, at 45 degrees (on no supported DOF): the supports take
  // the whole load, its moment about the base centre included (the symmetry
  // supports at y = 0 carry part of it: the totals count every support).
  const ShellModel model = cylinder_model();
  auto constraints = cylinder_supports(model.mesh);
  constraints.back().value = 0.0;
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), constraints);
  LoadSet loads;
  const Eigen::Vector3d top(std::sqrt(0.5), std::sqrt(0.5), 1.5);
  const int node = model.mesh.nearest_node(top);
  const Eigen::Vector3d force(2e4, -3e3, 5e3);
  loads.points.push_back(PointLoad{node, force, Eigen::Vector3d::Zero()});
  const StaticResult result = solve_static(system, loads);
  const StructureTotals totals = support_totals(model.mesh, result.reactions);
  // Forces on the supports: the load passes through them whole.
  CHECK((totals.support_force - force).norm() <= 1e-9 * force.norm());
  const Eigen::Vector3d moment = model.mesh.nodes[static_cast<std::size_t>(node)].cross(force);
  CHECK((totals.support_moment - moment).norm() <= 1e-9 * moment.norm());
  // Overturning about y: F_x z - F_z x.
  CHECK(totals.support_moment.y() == Approx(2e4 * 1.5 - 5e3 * std::sqrt(0.5)).epsilon(1e-9));
}

TEST_CASE("SLEPc modes and effective masses equal a dense generalised eigensolution", "[fem][parallel][modal]") {
  const ShellModel model = cylinder_model();
  auto constraints = cylinder_supports(model.mesh);
  constraints.back().value = 0.0;
  StructureSystem system(MPI_COMM_WORLD, cylinder_model(), constraints);
  const int count = 8;
  const ModalResult modes = solve_modes(system.assembler(), system.stiffness(), count);
  REQUIRE(static_cast<int>(modes.modes.size()) == count);

  // Dense reference over the free DOFs: K phi = omega^2 M phi, M the lumped diagonal.
  const Eigen::MatrixXd k = testing::dense_stiffness(model);
  const NodalValues& mass = system.assembler().nodal_mass();
  std::vector<Eigen::Index> free;
  for (std::size_t node = 0; node < model.mesh.nodes.size(); ++node)
    for (int c = 0; c < 6; ++c)
      if (system.dofs().equation(static_cast<int>(node), c) >= 0) free.push_back(static_cast<Eigen::Index>(6 * node) + c);
  const auto m = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd kff(m, m);
  Eigen::MatrixXd mff = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index a = 0; a < m; ++a) {
    mff(a, a) = mass[static_cast<std::size_t>(free[static_cast<std::size_t>(a)])];
    for (Eigen::Index b = 0; b < m; ++b) kff(a, b) = k(free[static_cast<std::size_t>(a)], free[static_cast<std::size_t>(b)]);
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(kff, mff);
  REQUIRE(dense.info() == Eigen::Success);
  Eigen::Vector3d free_mass = Eigen::Vector3d::Zero();
  for (int k3 = 0; k3 < 3; ++k3)
    for (Eigen::Index a = 0; a < m; ++a)
      if (free[static_cast<std::size_t>(a)] % 6 == k3) free_mass(k3) += mff(a, a);
  CHECK((modes.free_mass - free_mass).norm() <= 1e-12 * free_mass.norm());
  double previous = 0.0;
  for (int i = 0; i < count; ++i) {
    const double omega = std::sqrt(dense.eigenvalues()(i));
    // Both converge to 1e-10 or better: frequencies to 1e-8.
    CHECK(modes.modes[static_cast<std::size_t>(i)].omega == Approx(omega).epsilon(1e-8));
    CHECK(modes.modes[static_cast<std::size_t>(i)].omega >= previous);  // ascending
    previous = modes.modes[static_cast<std::size_t>(i)].omega;
    // Effective mass Gamma^2, Gamma = phi^T M iota with phi M-normalised (Eigen's are).
    const Eigen::VectorXd phi = dense.eigenvectors().col(i);
    for (int k3 = 0; k3 < 3; ++k3) {
      double gamma = 0.0;
      for (Eigen::Index a = 0; a < m; ++a)
        if (free[static_cast<std::size_t>(a)] % 6 == k3) gamma += mff(a, a) * phi(a);
      // Distinct frequencies (this model has no repeated ones): the modes,
      // hence their effective masses, are unique; to 1e-7 of the free mass.
      CHECK(std::abs(modes.modes[static_cast<std::size_t>(i)].effective_mass(k3) - gamma * gamma) <= 1e-7 * free_mass(k3));
    }
    CHECK(modes.modes[static_cast<std::size_t>(i)].period == Approx(2.0 * std::numbers::pi / omega).epsilon(1e-8));
  }
}
