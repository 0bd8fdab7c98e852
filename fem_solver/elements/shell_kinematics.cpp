#include "fem_solver/elements/shell_kinematics.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "fem_solver/elements/shape_functions.hpp"

namespace tankfsi::fem {
namespace {

using Operator = Eigen::Matrix<double, 3, Eigen::Dynamic>;  ///< 3 x 6n: nodal DOFs -> a vector

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// Covariant base vectors g_r, g_s, g_t (columns) at (r, s, t).
Eigen::Matrix3d covariant_basis(const ElementNodes& e, const ShapeValues& v, double t) {
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  const double a = e.thickness;
  for (int i = 0; i < e.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d p = e.position[k] + 0.5 * t * a * e.director[k];
    g.col(0) += v.dr[k] * p;
    g.col(1) += v.ds[k] * p;
    g.col(2) += 0.5 * a * v.h[k] * e.director[k];
  }
  return g;
}

/// Operators giving u_,r  u_,s  u_,t from the nodal DOFs: theta x V = -[V]x theta.
std::array<Operator, 3> derivative_operators(const ElementNodes& e, const ShapeValues& v, double t) {
  std::array<Operator, 3> d{Operator::Zero(3, e.dofs()), Operator::Zero(3, e.dofs()), Operator::Zero(3, e.dofs())};
  const double a = e.thickness;
  for (int i = 0; i < e.count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Matrix3d director_rotation = -cross_matrix(e.director[k]);
    d[0].block<3, 3>(0, 6 * i) = v.dr[k] * Eigen::Matrix3d::Identity();
    d[0].block<3, 3>(0, 6 * i + 3) = 0.5 * t * a * v.dr[k] * director_rotation;
    d[1].block<3, 3>(0, 6 * i) = v.ds[k] * Eigen::Matrix3d::Identity();
    d[1].block<3, 3>(0, 6 * i + 3) = 0.5 * t * a * v.ds[k] * director_rotation;
    d[2].block<3, 3>(0, 6 * i + 3) = 0.5 * a * v.h[k] * director_rotation;
  }
  return d;
}

/// Covariant tensor component e_ij (i, j in r s t) as a row.
DofRow covariant_component(const Eigen::Matrix3d& g, const std::array<Operator, 3>& d, int i, int j) {
  return 0.5 * (g.col(i).transpose() * d[static_cast<std::size_t>(j)] +
                g.col(j).transpose() * d[static_cast<std::size_t>(i)]);
}

DofRow covariant_at(const ElementNodes& e, double r, double s, double t, int i, int j) {
  const ShapeValues v = shape_values(e.count, r, s);
  return covariant_component(covariant_basis(e, v, t), derivative_operators(e, v, t), i, j);
}

/// MITC transverse shear: e_rt, e_st interpolated from tying points.
std::array<DofRow, 2> assumed_shear(const ElementNodes& e, double r, double s, double t) {
  if (e.count == 4) {
    // Dvorkin & Bathe (1984): e_rt tied at the mid-sides s = +-1 (A, C),
    // e_st at the mid-sides r = +-1 (D, B), each linear across the element.
    const DofRow rt_a = covariant_at(e, 0.0, 1.0, t, 0, 2);
    const DofRow rt_c = covariant_at(e, 0.0, -1.0, t, 0, 2);
    const DofRow st_d = covariant_at(e, 1.0, 0.0, t, 1, 2);
    const DofRow st_b = covariant_at(e, -1.0, 0.0, t, 1, 2);
    return {0.5 * (1.0 + s) * rt_a + 0.5 * (1.0 - s) * rt_c, 0.5 * (1.0 + r) * st_d + 0.5 * (1.0 - r) * st_b};
  }
  // MITC3 (Lee & Bathe 2004): e_rt = e_rt(1) + c s, e_st = e_st(2) - c r with
  // tying points (1) = (1/2, 0), (2) = (0, 1/2), (3) = (1/2, 1/2); tying the
  // tangential strain e_st - e_rt on the hypotenuse at (3) gives
  // c = e_rt(3) - e_rt(1) - e_st(3) + e_st(2). Isotropic: no preferred edge.
  const DofRow rt_1 = covariant_at(e, 0.5, 0.0, t, 0, 2);
  const DofRow st_2 = covariant_at(e, 0.0, 0.5, t, 1, 2);
  const DofRow rt_3 = covariant_at(e, 0.5, 0.5, t, 0, 2);
  const DofRow st_3 = covariant_at(e, 0.5, 0.5, t, 1, 2);
  const DofRow c = rt_3 - rt_1 - st_3 + st_2;
  return {rt_1 + c * s, st_2 - c * r};
}

}  // namespace

Eigen::Vector3d area_normal(const ElementNodes& e, double r, double s) {
  const Eigen::Matrix3d g = covariant_basis(e, shape_values(e.count, r, s), 0.0);
  return g.col(0).cross(g.col(1));
}

Eigen::Matrix3d local_frame(const ElementNodes& e, double r, double s, const Eigen::Vector3d& reference_axis) {
  const Eigen::Matrix3d g = covariant_basis(e, shape_values(e.count, r, s), 0.0);
  const Eigen::Vector3d e3 = g.col(0).cross(g.col(1)).normalized();
  Eigen::Vector3d e1 = reference_axis - reference_axis.dot(e3) * e3;
  // An axis within ~8 degrees of the normal orients nothing: use g_r instead.
  if (e1.norm() < 0.15 * reference_axis.norm()) e1 = g.col(0) - g.col(0).dot(e3) * e3;
  e1.normalize();
  Eigen::Matrix3d frame;
  frame.row(0) = e1.transpose();
  frame.row(1) = e3.cross(e1).transpose();
  frame.row(2) = e3.transpose();
  return frame;
}

StrainRows local_strain_rows(const ElementNodes& e, double r, double s, double t, const Eigen::Matrix3d& frame,
                             double& jacobian) {
  const ShapeValues v = shape_values(e.count, r, s);
  const Eigen::Matrix3d g = covariant_basis(e, v, t);
  jacobian = g.determinant();
  const auto d = derivative_operators(e, v, t);
  // Covariant tensor components; e_tt is left out (sigma_33 = 0, and e1, e2
  // are orthogonal to g^t, so it would only enter e33).
  std::array<std::array<DofRow, 3>, 3> cov;
  const DofRow zero = DofRow::Zero(e.dofs());
  cov[0][0] = covariant_component(g, d, 0, 0);
  cov[1][1] = covariant_component(g, d, 1, 1);
  cov[0][1] = cov[1][0] = covariant_component(g, d, 0, 1);
  const auto shear = assumed_shear(e, r, s, t);
  cov[0][2] = cov[2][0] = shear[0];
  cov[1][2] = cov[2][1] = shear[1];
  cov[2][2] = zero;
  // Contravariant base vectors g^i are the rows of g^-1: c(a, i) = e_a . g^i.
  const Eigen::Matrix3d c = frame * g.inverse().transpose();
  auto local = [&](int a, int b) {
    DofRow row = zero;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (c(a, i) != 0.0 && c(b, j) != 0.0)
          row += c(a, i) * c(b, j) * cov[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
    return row;
  };
  StrainRows rows(5, e.dofs());
  rows.row(0) = local(0, 0);
  rows.row(1) = local(1, 1);
  rows.row(2) = 2.0 * local(0, 1);
  rows.row(3) = 2.0 * local(0, 2);
  rows.row(4) = 2.0 * local(1, 2);
  return rows;
}

DofRow drilling_row(const ElementNodes& e, double r, double s, const Eigen::Matrix3d& frame) {
  const ShapeValues v = shape_values(e.count, r, s);
  const Eigen::Matrix3d g = covariant_basis(e, v, 0.0);
  const auto d = derivative_operators(e, v, 0.0);
  const Eigen::Matrix3d c = frame * g.inverse().transpose();
  // du/dx_a = sum_j c(a, j) u_,j; only r and s contribute in the surface.
  const Operator grad_1 = c(0, 0) * d[0] + c(0, 1) * d[1];
  const Operator grad_2 = c(1, 0) * d[0] + c(1, 1) * d[1];
  DofRow row = -0.5 * (frame.row(1) * grad_1 - frame.row(0) * grad_2);
  for (int i = 0; i < e.count; ++i)
    row.segment<3>(6 * i + 3) += v.h[static_cast<std::size_t>(i)] * frame.row(2);
  return row;
}

}  // namespace tankfsi::fem
