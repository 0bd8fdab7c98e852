// Large rotations: the rotation-vector maps, the co-rotational element
// (rigid motions strain nothing, the small-displacement limit is the linear
// element, the force is the energy's gradient) and the co-rotational static
// and Newmark analyses against closed forms: a cantilever strip bent into a
// circular arc by an end moment, and Mattiasson's (1981) elastica under a
// tip force. On 1, 2 and 4 ranks (the partition must not change them).
#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

#include "common/excitation/ground_motion.hpp"
#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/analysis/structure_solver.hpp"
#include "fem_solver/elements/corotational_element.hpp"
#include "fem_solver/elements/rotation_vector.hpp"
#include "fem_solver/mesh/structured_patch.hpp"
#include "patch_meshes.hpp"

using namespace tankfsi::fem;

namespace {

ElementNodes warped_quad() {
  // A distorted, slightly warped quadrilateral away from the origin.
  ElementNodes e;
  e.count = 4;
  e.thickness = 0.01;
  e.position = {Eigen::Vector3d(5.0, 2.0, 1.0), Eigen::Vector3d(5.3, 2.02, 1.0), Eigen::Vector3d(5.28, 2.25, 1.01),
                Eigen::Vector3d(4.97, 2.2, 0.99)};
  for (auto& d : e.director) d = Eigen::Vector3d(0.02, -0.01, 1.0).normalized();
  return e;
}

ShellSection plastic(double thickness) {
  ShellSection s = testing::steel_plate(thickness);
  s.young_modulus = 1.2e8;
  s.poisson_ratio = 0.0;
  s.density = 1000.0;
  return s;
}

/// A cantilever strip along x, length 1, width 0.1 (z), thickness 0.01,
/// E 1.2e8, nu 0: EI = 1 N m^2 over its width. Clamped at x = 0; the
/// edges z = const are symmetry planes (it bends in the x-y plane).
struct Cantilever {
  static constexpr double length = 1.0;
  static constexpr double bending_stiffness = 1.0;  // E t^3/12 * width
  ShellModel model;
  std::vector<DofConstraint> constraints;
  int tip_a = 0;
  int tip_b = 0;

  explicit Cantilever(int divisions) : model(mesh(divisions), {plastic(0.01)}) {
    const ShellMesh& m = model.mesh;
    for (const int n : m.nodes_of("u_start"))
      for (int k = 0; k < 6; ++k) constraints.push_back({n, k, 0.0});
    for (const char* edge : {"v_start", "v_end"})
      for (const int n : m.nodes_of(edge))
        for (const int k : {2, 3, 4}) constraints.push_back({n, k, 0.0});
    tip_a = m.nearest_node(Eigen::Vector3d(length, 0.0, 0.0));
    tip_b = m.nearest_node(Eigen::Vector3d(length, 0.0, 0.1));
  }
  static ShellMesh mesh(int divisions) {
    PatchSpec p;
    p.divisions_u = divisions;
    p.divisions_v = 1;
    p.region = "plate";
    p.map = [](double u, double v) { return Eigen::Vector3d(length * u, 0.0, 0.1 * v); };
    return structured_patch(p);
  }
  /// Half of a tip force and moment on each tip node.
  [[nodiscard]] LoadSet tip_load(const Eigen::Vector3d& force, const Eigen::Vector3d& moment) const {
    LoadSet loads;
    loads.points.push_back(PointLoad{tip_a, 0.5 * force, 0.5 * moment});
    loads.points.push_back(PointLoad{tip_b, 0.5 * force, 0.5 * moment});
    return loads;
  }
};

Eigen::Vector3d translation(const NodalValues& u, int node) {
  return Eigen::Vector3d(u[6 * static_cast<std::size_t>(node)], u[6 * static_cast<std::size_t>(node) + 1],
                         u[6 * static_cast<std::size_t>(node) + 2]);
}

}  // namespace

TEST_CASE("rotation vectors and matrices are inverse maps", "[fem][corotational]") {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  for (const double angle : {0.0, 1e-9, 1e-5, 0.3, 1.5, 3.0, 3.14159}) {
    const Eigen::Vector3d psi = angle * axis;
    const Eigen::Matrix3d r = rotation_matrix(psi);
    // Against Eigen's own angle-axis rotation.
    CHECK((r - Eigen::AngleAxisd(angle, axis).toRotationMatrix()).norm() < 1e-14);
    CHECK((rotation_vector(r) - psi).norm() < 1e-9 * std::max(1.0, angle));
  }
  // Exactly pi: either sign of the axis.
  const Eigen::Vector3d back = rotation_vector(rotation_matrix(std::numbers::pi * axis));
  CHECK(std::abs(back.norm() - std::numbers::pi) < 1e-12);
  CHECK(std::abs(std::abs(back.normalized().dot(axis)) - 1.0) < 1e-12);
}

TEST_CASE("a co-rotational element is strained by nothing but its deformation", "[fem][corotational]") {
  const ElementNodes e = warped_quad();
  const ShellSection section = plastic(e.thickness);
  const Eigen::MatrixXd k0 = element_stiffness(e, section);
  const CorotationalElement element(e, k0);
  const double scale = k0.norm();

  SECTION("a large rigid motion leaves no deformation, force or energy") {
    const Eigen::Matrix3d q = Eigen::AngleAxisd(1.2, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
    const Eigen::Vector3d shift(0.7, -0.2, 3.0);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& x : e.position) centre += 0.25 * x;
    ElementState state;
    for (std::size_t i = 0; i < 4; ++i) {
      state[i].displacement = q * (e.position[i] - centre) + centre + shift - e.position[i];
      state[i].rotation = q;
    }
    CHECK((element.rigid_rotation(state) - q).norm() < 1e-13);
    CHECK(element.deformation(state).norm() < 1e-13);
    const auto response = element.respond(state);
    CHECK(response.force.norm() < 1e-12 * scale);
    CHECK(response.energy < 1e-20 * scale);
  }

  SECTION("near the initial shape it is the linear element") {
    // The tangent at rest is K_0 (to the central differences' accuracy) ...
    const auto at_rest = element.respond(ElementState{});
    CHECK((at_rest.tangent - k0).norm() < 1e-7 * scale);
    // ... and a small displacement's force K_0 u to second order in u.
    Eigen::VectorXd u = Eigen::VectorXd::Random(24);
    for (const double size : {1e-4, 1e-5}) {
      ElementState state;
      for (std::size_t i = 0; i < 4; ++i) {
        const auto k = static_cast<Eigen::Index>(6 * i);
        state[i].displacement = size * u.segment<3>(k);
        state[i].rotation = rotation_matrix(size * u.segment<3>(k + 3));
      }
      const Eigen::VectorXd linear = k0 * (size * u);
      const double relative = (element.respond(state).force - linear).norm() / linear.norm();
      INFO("displacement scale " << size << ": force against K_0 u " << relative);
      CHECK(relative < 30.0 * size);  // O(u): the force's second-order part over its first
    }
  }

  SECTION("its Jacobian is that of central differences of its deformation") {
    ElementState state;
    const Eigen::Matrix3d q = Eigen::AngleAxisd(2.0, Eigen::Vector3d(-0.3, 0.4, 1.0).normalized()).toRotationMatrix();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& x : e.position) centre += 0.25 * x;
    const Eigen::VectorXd bend = 0.05 * Eigen::VectorXd::Random(24);
    for (std::size_t i = 0; i < 4; ++i) {
      const auto k = static_cast<Eigen::Index>(6 * i);
      state[i].displacement = q * (e.position[i] - centre) + centre - e.position[i] + 0.03 * bend.segment<3>(k);
      state[i].rotation = rotation_matrix(bend.segment<3>(k + 3)) * q;
    }
    Eigen::MatrixXd differences(24, 24);
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 6; ++c) {
        const double h = c < 3 ? 1e-6 * 0.15 : 1e-6;
        ElementState plus = state;
        ElementState minus = state;
        const auto k = static_cast<std::size_t>(i);
        if (c < 3) {
          plus[k].displacement(c) += h;
          minus[k].displacement(c) -= h;
        } else {
          plus[k].rotation = rotation_matrix(h * Eigen::Vector3d::Unit(c - 3)) * state[k].rotation;
          minus[k].rotation = rotation_matrix(-h * Eigen::Vector3d::Unit(c - 3)) * state[k].rotation;
        }
        differences.col(6 * i + c) = (element.deformation(plus) - element.deformation(minus)) / (2.0 * h);
      }
    const Eigen::MatrixXd exact = element.deformation_jacobian(state);
    INFO("largest difference " << (exact - differences).cwiseAbs().maxCoeff());
    // Central differences: rounding eps/h ~ 2e-10 of the entries (of order 1).
    CHECK((exact - differences).cwiseAbs().maxCoeff() < 1e-8);
  }

  SECTION("its force is the gradient of its energy in a bent, rotated state") {
    ElementState state;
    const Eigen::Matrix3d q = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.2, 1.0, 0.4).normalized()).toRotationMatrix();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const auto& x : e.position) centre += 0.25 * x;
    Eigen::VectorXd bend = 0.01 * Eigen::VectorXd::Random(24);
    for (std::size_t i = 0; i < 4; ++i) {
      const auto k = static_cast<Eigen::Index>(6 * i);
      state[i].displacement = q * (e.position[i] - centre) + centre - e.position[i] + 0.03 * bend.segment<3>(k);
      state[i].rotation = rotation_matrix(bend.segment<3>(k + 3)) * q;
    }
    const auto response = element.respond(state);
    REQUIRE(response.energy > 0.0);
    const Eigen::VectorXd direction = Eigen::VectorXd::Random(24);
    auto energy_at = [&](double h) {
      ElementState moved = state;
      for (std::size_t i = 0; i < 4; ++i) {
        const auto k = static_cast<Eigen::Index>(6 * i);
        moved[i].displacement += h * 0.03 * direction.segment<3>(k);
        moved[i].rotation = rotation_matrix(h * direction.segment<3>(k + 3)) * state[i].rotation;
      }
      return element.respond(moved).energy;
    };
    const double h = 1e-5;
    const double slope = (energy_at(h) - energy_at(-h)) / (2.0 * h);
    Eigen::VectorXd scaled = direction;
    for (int i = 0; i < 4; ++i) scaled.segment<3>(6 * i) *= 0.03;
    INFO("energy slope " << slope << ", force along the direction " << response.force.dot(scaled));
    CHECK(std::abs(slope - response.force.dot(scaled)) < 1e-7 * std::abs(slope));
  }
}

TEST_CASE("an end moment bends a cantilever strip into a circular arc", "[fem][corotational]") {
  // Pure bending: curvature M / EI everywhere, the tip at rotation phi = M L / EI,
  // x = L sin(phi)/phi, y = L (1 - cos phi)/phi. The linear elements bend
  // exactly at constant curvature; what remains is chords against the arc.
  const Cantilever c(20);
  const double phi = std::numbers::pi / 2.0;
  const double moment = phi * Cantilever::bending_stiffness / Cantilever::length;
  StructureSystem system(MPI_COMM_WORLD, c.model, c.constraints);
  const StaticResult result =
      solve_static_corotational(system, c.tip_load(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, moment)), 4);
  const Eigen::Vector3d tip = translation(result.displacement, c.tip_a);
  const double exact_u = Cantilever::length * (std::sin(phi) / phi - 1.0);
  const double exact_v = Cantilever::length * (1.0 - std::cos(phi)) / phi;
  const double rotation = result.displacement[6 * static_cast<std::size_t>(c.tip_a) + 5];
  INFO("tip u " << tip.x() << " (exact " << exact_u << "), v " << tip.y() << " (exact " << exact_v << "), rotation "
                << rotation << " (exact " << phi << "), " << result.solver);
  // 20 chords over a quarter circle: the elements' own mid-side sagitta,
  // L phi^2/(8 n^2) relative ~ 8e-4; allow 0.3 % (measured -0.05 %).
  CHECK(std::abs(tip.x() / exact_u - 1.0) < 3e-3);
  CHECK(std::abs(tip.y() / exact_v - 1.0) < 3e-3);
  CHECK(std::abs(rotation / phi - 1.0) < 1e-3);
  CHECK(std::abs(tip.z()) < 1e-12);
  // Both tip nodes alike (the strip is in plane strain).
  CHECK((translation(result.displacement, c.tip_b) - tip).norm() < 1e-9);
  // The strip puts the moment on its support (support forces: what the
  // structure puts on its supports, as the linear analysis reports them).
  double reaction_moment = 0.0;
  for (std::size_t i = 5; i < result.reactions.size(); i += 6) reaction_moment += result.reactions[i];
  CHECK(std::abs(reaction_moment - moment) < 1e-6 * moment);
}

TEST_CASE("a tip force bends a cantilever strip as the elastica", "[fem][corotational][heavy]") {
  // Mattiasson (1981), PL^2/EI = 1, 2 and 10: w/L 0.30172, 0.49346, 0.81061 and
  // u/L 0.05643, 0.16064, 0.55500 (a shooting solution of theta'' = -k cos theta
  // gives the same five digits). The force keeps its direction (-y).
  const Cantilever c(20);
  StructureSystem system(MPI_COMM_WORLD, c.model, c.constraints);
  struct Point {
    double load, deflection, shortening;
  };
  for (const Point p : {Point{1.0, 0.30172, 0.05643}, Point{2.0, 0.49346, 0.16064}, Point{10.0, 0.81061, 0.55500}}) {
    const StaticResult result =
        solve_static_corotational(system, c.tip_load(Eigen::Vector3d(0.0, -p.load, 0.0), Eigen::Vector3d::Zero()), 10);
    const Eigen::Vector3d tip = translation(result.displacement, c.tip_a);
    INFO("PL^2/EI = " << p.load << ": w/L " << -tip.y() << " (" << p.deflection << "), u/L " << -tip.x() << " ("
                      << p.shortening << "), " << result.solver);
    // 20 elements: within 0.3 % (measured: -0.04 % at most for w, -0.12 % for u;
    // the table's 5 digits are 1e-4 of it).
    CHECK(std::abs(-tip.y() / p.deflection - 1.0) < 3e-3);
    CHECK(std::abs(-tip.x() / p.shortening - 1.0) < 3e-3);
  }
}

TEST_CASE("small co-rotational motion is the linear motion", "[fem][corotational]") {
  // A tip force small enough that geometry does not change the answer:
  // both Newmark integrators through StructureSolver give the same history.
  const Cantilever c(10);
  const tankfsi::ZeroGroundMotion still;
  const RayleighCoefficients damping{0.5, 1e-4};
  const LoadSet load = c.tip_load(Eigen::Vector3d(0.0, -1e-3, 0.0), Eigen::Vector3d::Zero());
  StructureSystem linear_system(MPI_COMM_WORLD, c.model, c.constraints);
  StructureSystem corotational_system(MPI_COMM_WORLD, c.model, c.constraints);
  const auto rule = TimeIntegrationRule::generalized_alpha(0.8);
  StructureSolver linear(linear_system, damping, load, still, rule);
  StructureSolver corotational(corotational_system, damping, load, still, rule, Kinematics::corotational);
  double largest = 0.0;
  double difference = 0.0;
  for (int step = 0; step < 40; ++step) {
    linear.advance(2e-3);
    corotational.advance(2e-3);
    const double a = translation(linear.displacement(), c.tip_a).y();
    const double b = translation(corotational.displacement(), c.tip_a).y();
    largest = std::max(largest, std::abs(a));
    difference = std::max(difference, std::abs(a - b));
  }
  INFO("largest tip deflection " << largest << " m, largest difference " << difference << " m");
  REQUIRE(largest > 1e-6);
  // The geometric effect is of the order of the deflection squared over L: 1e-5 of it here.
  CHECK(difference < 1e-4 * largest);
  CHECK(std::abs(linear.energy() / corotational.energy() - 1.0) < 1e-3);
}

TEST_CASE("a swinging cantilever keeps its energy through large rotations", "[fem][corotational][heavy]") {
  // Released from a large static deflection (PL^2/EI = 2, the tip turned by
  // 45 degrees), undamped: the average-acceleration rule conserves energy for
  // linear systems; with large rotations it stays bounded, to the steps'
  // accuracy. The linear solver would strain the rotated elements instead.
  const Cantilever c(10);
  const tankfsi::ZeroGroundMotion still;
  const LoadSet load = c.tip_load(Eigen::Vector3d(0.0, -2.0, 0.0), Eigen::Vector3d::Zero());
  StructureSystem system(MPI_COMM_WORLD, c.model, c.constraints);
  StructureSolver solver(system, RayleighCoefficients{}, load, still, TimeIntegrationRule::average_acceleration(),
                         Kinematics::corotational);
  solver.start_at_equilibrium();
  const double deflected = translation(solver.displacement(), c.tip_a).y();
  REQUIRE(deflected < -0.45);
  const double strain_energy = solver.energy();
  // Release: the same state without the load, the strain energy becomes motion.
  StructureSolver::Checkpoint start;
  solver.save(start);
  StructureSystem released_system(MPI_COMM_WORLD, c.model, c.constraints);
  StructureSolver released(released_system, RayleighCoefficients{}, LoadSet{}, still,
                           TimeIntegrationRule::average_acceleration(), Kinematics::corotational);
  released.restore(start);
  released.balance_acceleration();
  // The first bending period is 1.79 s (omega = 1.875^2 sqrt(EI/(m L^4)), m = 1 kg/m):
  // 200 steps of 5 ms cover more than half of it.
  double highest = deflected;
  double energy_error = 0.0;
  for (int step = 0; step < 200; ++step) {
    released.advance(5e-3);
    highest = std::max(highest, translation(released.displacement(), c.tip_a).y());
    energy_error = std::max(energy_error, std::abs(released.energy() / strain_energy - 1.0));
  }
  INFO("released from " << deflected << " m, highest " << highest << " m, energy " << strain_energy
                        << " J, largest energy error " << energy_error);
  CHECK(highest > -deflected * 0.9);  // it swings through to the other side
  CHECK(energy_error < 1e-2);
}
