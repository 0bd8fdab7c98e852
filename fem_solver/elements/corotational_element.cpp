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
  Eigen::MatrixXd j(6 * count_, 6 * count_);
  for (int i = 0; i < count_; ++i)
    for (int c = 0; c < 6; ++c) {
      const double h = step_of(c);
      j.col(6 * i + c) = (deformation(moved(now, i, c, h)) - deformation(moved(now, i, c, -h))) / (2.0 * h);
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
