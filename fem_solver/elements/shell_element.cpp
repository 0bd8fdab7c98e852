#include "fem_solver/elements/shell_element.hpp"

#include <cmath>

#include "fem_solver/elements/shape_functions.hpp"

namespace tankfsi::fem {
namespace {

/// Gauss points through the thickness: the strains are linear in t, so two
/// points integrate the quadratic energy density exactly.
const std::array<double, 2> thickness_points{-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};

double plane_von_mises(const Eigen::Matrix<double, 5, 1>& stress) {
  const double s11 = stress(0), s22 = stress(1), s12 = stress(2);
  return std::sqrt(s11 * s11 - s11 * s22 + s22 * s22 + 3.0 * s12 * s12);
}

}  // namespace

Eigen::MatrixXd element_stiffness(const ElementNodes& e, const ShellSection& section, double drilling_factor) {
  const auto d = shell_material_matrix(section);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(e.dofs(), e.dofs());
  for (const auto& q : surface_quadrature(e.count)) {
    const Eigen::Matrix3d frame = local_frame(e, q.r, q.s, section.reference_axis);
    for (const double t : thickness_points) {
      double jacobian = 0.0;
      const StrainRows b = local_strain_rows(e, q.r, q.s, t, frame, jacobian);
      k.noalias() += b.transpose() * d * b * (jacobian * q.weight);
    }
    const DofRow drill = drilling_row(e, q.r, q.s, frame);
    const double area = area_normal(e, q.r, q.s).norm() * q.weight;
    k.noalias() += drill.transpose() * drill * (drilling_factor * section.shear_modulus() * section.thickness * area);
  }
  return k;
}

Eigen::VectorXd element_lumped_mass(const ElementNodes& e, const ShellSection& section) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(e.dofs());
  const double t = section.thickness;
  for (const auto& q : surface_quadrature(e.count)) {
    const ShapeValues v = shape_values(e.count, q.r, q.s);
    const double area = area_normal(e, q.r, q.s).norm() * q.weight;
    for (int i = 0; i < e.count; ++i) {
      const double share = v.h[static_cast<std::size_t>(i)] * area;
      m.segment<3>(6 * i).array() += section.density * t * share;
      m.segment<3>(6 * i + 3).array() += section.density * t * t * t / 12.0 * share;
    }
  }
  return m;
}

Eigen::VectorXd element_surface_load(const ElementNodes& e, const PressureField& pressure,
                                     const Eigen::Vector3d& traction) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(e.dofs());
  for (const auto& q : surface_quadrature(e.count)) {
    const ShapeValues v = shape_values(e.count, q.r, q.s);
    const Eigen::Vector3d n = area_normal(e, q.r, q.s);  // |n| is the area element
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < e.count; ++i) x += v.h[static_cast<std::size_t>(i)] * e.position[static_cast<std::size_t>(i)];
    const double p = pressure ? pressure(x) : 0.0;
    const Eigen::Vector3d load = (p * n + traction * n.norm()) * q.weight;
    for (int i = 0; i < e.count; ++i) f.segment<3>(6 * i) += v.h[static_cast<std::size_t>(i)] * load;
  }
  return f;
}

double element_area(const ElementNodes& e) {
  double area = 0.0;
  for (const auto& q : surface_quadrature(e.count)) area += area_normal(e, q.r, q.s).norm() * q.weight;
  return area;
}

StressResultants element_stress_resultants(const ElementNodes& e, const ShellSection& section,
                                           const Eigen::VectorXd& displacement) {
  const auto d = shell_material_matrix(section);
  const QuadraturePoint c = element_centre(e.count);
  const Eigen::Matrix3d frame = local_frame(e, c.r, c.s, section.reference_axis);
  auto stress_at = [&](double t) -> Eigen::Matrix<double, 5, 1> {
    double jacobian = 0.0;
    return d * (local_strain_rows(e, c.r, c.s, t, frame, jacobian) * displacement);
  };
  const Eigen::Matrix<double, 5, 1> top = stress_at(1.0);
  const Eigen::Matrix<double, 5, 1> middle = stress_at(0.0);
  const Eigen::Matrix<double, 5, 1> bottom = stress_at(-1.0);
  const double h = section.thickness;
  StressResultants out;
  // In-plane stresses are linear through the thickness: N = h sigma(0),
  // M = integral of sigma z dz = h^2/12 (sigma_top - sigma_bottom).
  out.membrane = h * middle.head<3>();
  out.bending = h * h / 12.0 * (top.head<3>() - bottom.head<3>());
  // The shear strain is constant in t (assumed); D carries the 5/6 factor.
  out.shear = h * middle.tail<2>();
  out.von_mises_top = plane_von_mises(top);
  out.von_mises_bottom = plane_von_mises(bottom);
  return out;
}

}  // namespace tankfsi::fem
