#include "fem_solver/elements/corotational_element.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>

#include "fem_solver/elements/rotation_vector.hpp"

namespace tankfsi::fem {

CorotationalElement::CorotationalElement(const ElementNodes& initial, Eigen::MatrixXd stiffness)
    : count_(initial.count), stiffness_(std::move(stiffness)) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < count_; ++i) centre += initial.position[static_cast<std::size_t>(i)];
  centre /= count_;
  size_ = 0.0;
  for (int i = 0; i < count_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    initial_position_[k] = initial.position[k] - centre;
    size_ = std::max(size_, initial_position_[k].norm());
  }
  initial_frame_ = frame(initial_position_);
}

std::array<Eigen::Vector3d, 4> CorotationalElement::positions(const ElementState& now) const {
  std::array<Eigen::Vector3d, 4> x{};
  for (int i = 0; i < count_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    x[k] = initial_position_[k] + now[k].displacement;
  }
  return x;
}

Eigen::Matrix3d CorotationalElement::frame(const std::array<Eigen::Vector3d, 4>& x) const {
  Eigen::Vector3d normal;
  Eigen::Vector3d along;
  if (count_ == 4) {
    normal = (x[2] - x[0]).cross(x[3] - x[1]);
    along = x[1] + x[2] - x[0] - x[3];  // g_r at the centre, times 2
  } else {
    normal = (x[1] - x[0]).cross(x[2] - x[0]);
    along = x[1] - x[0];
  }
  Eigen::Matrix3d e;
  e.col(2) = normal.normalized();
  e.col(0) = (along - along.dot(e.col(2)) * e.col(2)).normalized();
  e.col(1) = e.col(2).cross(e.col(0));
  return e;
}

Eigen::Matrix3d CorotationalElement::rigid_rotation(const ElementState& now) const {
  return frame(positions(now)) * initial_frame_.transpose();
}

Eigen::VectorXd CorotationalElement::deformation(const ElementState& now) const {
  const std::array<Eigen::Vector3d, 4> x = positions(now);
  const Eigen::Matrix3d rigid = frame(x) * initial_frame_.transpose();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < count_; ++i) centre += x[static_cast<std::size_t>(i)];
  centre /= count_;
  Eigen::VectorXd d(6 * count_);
  for (int i = 0; i < count_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    d.segment<3>(6 * i) = rigid.transpose() * (x[k] - centre) - initial_position_[k];
    d.segment<3>(6 * i + 3) = rotation_vector(rigid.transpose() * now[k].rotation);
  }
  return d;
}

double CorotationalElement::step_of(int component) const { return component < 3 ? 1e-6 * size_ : 1e-6; }

ElementState CorotationalElement::moved(const ElementState& now, int node, int component, double h) const {
  ElementState out = now;
  const auto k = static_cast<std::size_t>(node);
  if (component < 3)
    out[k].displacement(component) += h;
  else
    out[k].rotation = rotation_matrix(h * Eigen::Vector3d::Unit(component - 3)) * now[k].rotation;
  return out;
}

Eigen::MatrixXd CorotationalElement::deformation_jacobian(const ElementState& now) const {
  const std::array<Eigen::Vector3d, 4> x = positions(now);
  const Eigen::Matrix3d e = frame(x);
  const Eigen::Vector3d e1 = e.col(0), e2 = e.col(1), e3 = e.col(2);
  const Eigen::Matrix3d rigid_t = (e * initial_frame_.transpose()).transpose();
  // The frame's pieces (frame()): normal n = a x b, in-plane direction g;
  // per node, da/dx_i, db/dx_i and dg/dx_i are multiples of the identity.
  std::array<double, 4> da{}, db{}, dg{};
  Eigen::Vector3d a, b, g;
  if (count_ == 4) {
    a = x[2] - x[0], b = x[3] - x[1], g = x[1] + x[2] - x[0] - x[3];
    da = {-1.0, 0.0, 1.0, 0.0}, db = {0.0, -1.0, 0.0, 1.0}, dg = {-1.0, 1.0, 1.0, -1.0};
  } else {
    a = x[1] - x[0], b = x[2] - x[0], g = x[1] - x[0];
    da = {-1.0, 1.0, 0.0, 0.0}, db = {-1.0, 0.0, 1.0, 0.0}, dg = {-1.0, 1.0, 0.0, 0.0};
  }
  const double normal_length = a.cross(b).norm();
  const double along_length = (g - g.dot(e3) * e3).norm();
  // The frame's spin dphi = Phi_i dx_i: its components along e1, e2, e3 are
  // de2.e3 = -e2.de3, de3.e1 and de1.e2, with de3 = (I - e3 e3^T) dn / |n|,
  // dn = a x db - b x da, and de1.e2 = (e2.dg - (g.e3) e2.de3) / |p|,
  // p = g - (g.e3) e3 the in-plane direction before normalising.
  std::array<Eigen::Matrix3d, 4> spin{};
  for (int i = 0; i < count_; ++i) {
    const auto k = static_cast<std::size_t>(i);
    Eigen::Matrix3d dn;  // dn/dx_i
    dn << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
    Eigen::Matrix3d b_cross;
    b_cross << 0.0, -b.z(), b.y(), b.z(), 0.0, -b.x(), -b.y(), b.x(), 0.0;
    dn = db[k] * dn - da[k] * b_cross;
    const Eigen::RowVector3d e2_de3 = e2.transpose() * dn / normal_length;
    const Eigen::RowVector3d e1_de3 = e1.transpose() * dn / normal_length;
    const Eigen::RowVector3d e1_e2 = (dg[k] * e2.transpose() - g.dot(e3) * e2_de3) / along_length;
    spin[k] = -e1 * e2_de3 + e2 * e1_de3 + e3 * e1_e2;
  }
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < count_; ++i) centre += x[static_cast<std::size_t>(i)];
  centre /= count_;
  // u_d,j = R_e^T (x_j - c) - X_j:  du_d,j = R_e^T (dx_j - dc + [x_j - c]x dphi);
  // theta_d,j = log(R_e^T R_j):     dtheta_d,j = J_l^-1(theta_d,j) R_e^T (dw_j - dphi),
  // J_l the left Jacobian of the rotations (its inverse below).
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(6 * count_, 6 * count_);
  for (int row = 0; row < count_; ++row) {
    const auto r = static_cast<std::size_t>(row);
    const Eigen::Vector3d arm = x[r] - centre;
    Eigen::Matrix3d arm_cross;
    arm_cross << 0.0, -arm.z(), arm.y(), arm.z(), 0.0, -arm.x(), -arm.y(), arm.x(), 0.0;
    const Eigen::Matrix3d log_map = inverse_left_jacobian(rotation_vector(rigid_t * now[r].rotation)) * rigid_t;
    for (int column = 0; column < count_; ++column) {
      const auto c = static_cast<std::size_t>(column);
      const double own = (row == column ? 1.0 : 0.0) - 1.0 / count_;
      j.block<3, 3>(6 * row, 6 * column) = rigid_t * (own * Eigen::Matrix3d::Identity() + arm_cross * spin[c]);
      j.block<3, 3>(6 * row + 3, 6 * column) = -log_map * spin[c];
    }
    j.block<3, 3>(6 * row + 3, 6 * row + 3) = log_map;
  }
  return j;
}

Eigen::VectorXd CorotationalElement::force(const ElementState& now) const {
  return deformation_jacobian(now).transpose() * (stiffness_ * deformation(now));
}

CorotationalElement::Response CorotationalElement::respond(const ElementState& now, Tangent tangent) const {
  const Eigen::VectorXd d = deformation(now);
  const Eigen::MatrixXd j = deformation_jacobian(now);
  const Eigen::VectorXd kd = stiffness_ * d;
  Response r;
  r.force = j.transpose() * kd;
  r.energy = 0.5 * d.dot(kd);
  if (tangent == Tangent::material) {
    r.tangent = j.transpose() * stiffness_ * j;
    return r;
  }
  r.tangent.resize(6 * count_, 6 * count_);
  for (int i = 0; i < count_; ++i)
    for (int c = 0; c < 6; ++c) {
      const double h = step_of(c);
      r.tangent.col(6 * i + c) = (force(moved(now, i, c, h)) - force(moved(now, i, c, -h))) / (2.0 * h);
    }
  r.tangent = 0.5 * (r.tangent + r.tangent.transpose()).eval();
  return r;
}

double CorotationalElement::force_rounding() const {
  return stiffness_.cwiseAbs().maxCoeff() * std::numeric_limits<double>::epsilon() * size_;
}

}  // namespace tankfsi::fem
