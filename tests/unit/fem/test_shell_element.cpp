// Element-level checks of the MITC4 quadrilateral and MITC3 triangle: rigid
// modes and the stiffness spectrum, patch tests, lumped mass.
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <functional>

#include "patch_meshes.hpp"

using namespace tankfsi::fem;
using tankfsi::fem::testing::dense_stiffness;
using tankfsi::fem::testing::macneal_patch;
using tankfsi::fem::testing::steel_plate;

namespace {

/// A distorted, slightly warped single element (warp 2 % of its size), so the
/// checks do not rest on a rectangle's symmetry.
ElementNodes distorted_element(int count) {
  ElementNodes e;
  e.count = count;
  e.thickness = 0.05;
  e.position = {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(1.1, 0.1, 0.02), Eigen::Vector3d(0.9, 1.0, -0.01),
                Eigen::Vector3d(-0.1, 0.8, 0.015)};
  // Directors: the element's corner normals (as compute_directors gives a lone element).
  for (int k = 0; k < count; ++k) {
    const auto at = [&](int i) { return e.position[static_cast<std::size_t>((i + count) % count)]; };
    e.director[static_cast<std::size_t>(k)] = (at(k + 1) - at(k)).cross(at(k - 1) - at(k)).normalized();
  }
  return e;
}

Eigen::MatrixXd rigid_modes(const ElementNodes& e) {
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(e.dofs(), 6);
  for (int i = 0; i < e.count; ++i)
    for (int k = 0; k < 3; ++k) {
      r(6 * i + k, k) = 1.0;
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k);
      r.block<3, 1>(6 * i, 3 + k) = axis.cross(e.position[static_cast<std::size_t>(i)]);
      r.block<3, 1>(6 * i + 3, 3 + k) = axis;
    }
  return r;
}

}  // namespace

TEST_CASE("rigid-body motions are exactly six zero-energy modes of both elements", "[fem][element]") {
  for (const int count : {4, 3}) {
    INFO("element with " << count << " nodes");
    const ElementNodes e = distorted_element(count);
    const Eigen::MatrixXd k = element_stiffness(e, steel_plate(e.thickness));
    REQUIRE((k - k.transpose()).norm() <= 1e-12 * k.norm());
    // K r = 0 for every rigid motion, to round-off of the largest entries.
    const Eigen::MatrixXd r = rigid_modes(e);
    CHECK((k * r).norm() <= 1e-10 * k.norm() * r.norm());
    // Spectrum: six zeros (round-off, < 1e-12 of the largest eigenvalue), then
    // a gap. The softest physical mode is the drilling penalty, of order
    // 1e-3 G t A against the membrane's E t: well above 1e-8 of the largest,
    // while a spurious (hourglass) mode would sit at round-off with the rigid ones.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(k);
    const Eigen::VectorXd lambda = eig.eigenvalues();
    const double largest = lambda.maxCoeff();
    for (int i = 0; i < 6; ++i) CHECK(std::abs(lambda(i)) <= 1e-12 * largest);
    CHECK(lambda(6) >= 1e-8 * largest);
  }
}

namespace {

/// Solves the patch with the boundary nodes (0..3) given by `exact` and checks
/// that the interior nodes reproduce it; returns the largest interior error.
double patch_error(bool triangles, const std::function<Eigen::Matrix<double, 6, 1>(const Eigen::Vector3d&)>& exact,
                   double thickness) {
  const ShellModel model(macneal_patch(triangles), {steel_plate(thickness)});
  const Eigen::MatrixXd k = dense_stiffness(model);
  const Eigen::Index boundary = 24;  // nodes 0..3
  const Eigen::Index interior = k.rows() - boundary;
  Eigen::VectorXd u_boundary(boundary);
  Eigen::VectorXd u_exact(interior);
  for (int n = 0; n < 8; ++n) {
    const Eigen::Matrix<double, 6, 1> u = exact(model.mesh.nodes[static_cast<std::size_t>(n)]);
    if (n < 4) u_boundary.segment<6>(6 * n) = u;
    else u_exact.segment<6>(6 * (n - 4)) = u;
  }
  const Eigen::VectorXd rhs = -k.block(boundary, 0, interior, boundary) * u_boundary;
  const Eigen::VectorXd u = k.block(boundary, boundary, interior, interior).ldlt().solve(rhs);
  return (u - u_exact).lpNorm<Eigen::Infinity>() / u_exact.lpNorm<Eigen::Infinity>();
}

}  // namespace

// Patch tests (MacNeal & Harder 1985): a state the element represents exactly
// must be reproduced exactly at the interior nodes of a distorted patch. Exact
// means round-off of the dense solve (condition ~1e8 at t = 1e-3): 1e-7.
TEST_CASE("membrane patch test: linear in-plane displacement with its drilling rotation", "[fem][element]") {
  const auto exact = [](const Eigen::Vector3d& x) {
    Eigen::Matrix<double, 6, 1> u = Eigen::Matrix<double, 6, 1>::Zero();
    u(0) = 1e-3 * (x.x() + 0.5 * x.y());
    u(1) = 1e-3 * (x.y() + 0.5 * x.x()) * 0.7 + 2e-4 * x.x();
    // Drilling rotation = in-plane rotation (v_,x - u_,y)/2 of this field.
    u(5) = 0.5 * ((0.35e-3 + 2e-4) - 0.5e-3);
    return u;
  };
  for (const bool triangles : {false, true}) {
    INFO((triangles ? "triangles" : "quadrilaterals"));
    CHECK(patch_error(triangles, exact, 0.001) <= 1e-7);
  }
}

TEST_CASE("bending patch test: constant curvature, zero transverse shear", "[fem][element]") {
  // w = (a x^2 + b y^2 + c x y)/2 with theta_x = w_,y, theta_y = -w_,x: the
  // director (normal e_z) then stays normal, as Kirchhoff's plate.
  const double a = 1e-3, b = 2e-3, c = 1.5e-3;
  const auto exact = [&](const Eigen::Vector3d& x) {
    Eigen::Matrix<double, 6, 1> u = Eigen::Matrix<double, 6, 1>::Zero();
    u(2) = 0.5 * (a * x.x() * x.x() + b * x.y() * x.y() + c * x.x() * x.y());
    u(3) = b * x.y() + 0.5 * c * x.x();
    u(4) = -(a * x.x() + 0.5 * c * x.y());
    return u;
  };
  for (const bool triangles : {false, true}) {
    INFO((triangles ? "triangles" : "quadrilaterals"));
    CHECK(patch_error(triangles, exact, 0.001) <= 1e-7);
  }
}

TEST_CASE("transverse shear patch test: constant shear strain on distorted elements", "[fem][element]") {
  // w = g x + h y with zero rotations is a constant transverse shear state
  // (gamma_xz = g, gamma_yz = h). It needs a distributed moment to be in
  // equilibrium, so it is not a solve-for-the-interior patch; instead every
  // element of the distorted patch must represent it exactly: Q = k G t gamma,
  // no membrane force, no bending moment (round-off: 1e-10 relative).
  const double g = 1e-3, h = 0.4e-3;
  for (const bool triangles : {false, true}) {
    INFO((triangles ? "triangles" : "quadrilaterals"));
    ShellSection section = steel_plate(0.01);
    section.reference_axis = Eigen::Vector3d::UnitX();
    const ShellModel model(macneal_patch(triangles), {section});
    const double expected = shear_correction * section.shear_modulus() * section.thickness;
    for (std::size_t e = 0; e < model.mesh.elements.size(); ++e) {
      const ElementNodes nodes = model.element_nodes(e);
      Eigen::VectorXd u = Eigen::VectorXd::Zero(nodes.dofs());
      for (int i = 0; i < nodes.count; ++i) {
        const Eigen::Vector3d& x = nodes.position[static_cast<std::size_t>(i)];
        u(6 * i + 2) = g * x.x() + h * x.y();
      }
      const StressResultants r = element_stress_resultants(nodes, section, u);
      CHECK(r.shear(0) == Approx(expected * g).epsilon(1e-10));
      CHECK(r.shear(1) == Approx(expected * h).epsilon(1e-10));
      CHECK(r.membrane.norm() <= 1e-10 * expected * g);
      CHECK(r.bending.norm() <= 1e-10 * expected * g * section.thickness);
    }
  }
}

TEST_CASE("lumped mass sums to the physical mass, with rotary inertia", "[fem][element]") {
  for (const int count : {4, 3}) {
    const ElementNodes e = distorted_element(count);
    const ShellSection s = steel_plate(e.thickness);
    const Eigen::VectorXd m = element_lumped_mass(e, s);
    const double mass = s.density * s.thickness * element_area(e);
    for (int k = 0; k < 3; ++k) {
      double translational = 0.0;
      double rotary = 0.0;
      for (int i = 0; i < count; ++i) {
        translational += m(6 * i + k);
        rotary += m(6 * i + 3 + k);
      }
      CHECK(translational == Approx(mass).epsilon(1e-12));
      CHECK(rotary == Approx(mass * s.thickness * s.thickness / 12.0).epsilon(1e-12));
    }
    CHECK(m.minCoeff() > 0.0);
  }
}
