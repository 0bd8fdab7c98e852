#include "sph_solver/isph/particle_terms.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Calls f(j, x_ij, r) for every neighbour j of owned particle i.
template <class F>
void for_each_neighbour(const Neighbourhood& n, int i, F&& f) {
  const Eigen::Vector3d& x_i = n.position[at(i)];
  for (const int j : n.neighbours.neighbours_of(i)) {
    const Eigen::Vector3d x_ij = x_i - n.position[at(j)];
    f(j, x_ij, x_ij.norm());
  }
}

/// The wall distance in the no-slip extrapolation factor (1 + d / r_iw), floored at
/// L0/4 so that a particle touching the wall gets a finite (5-fold at most
/// typical depths) rather than an infinite velocity gradient.
double extrapolation_distance(const Neighbourhood& n, const WallContact& c) {
  return std::max(c.distance, 0.25 * n.model.spacing);
}

/// The pressure gradient of a particle near walls from its fluid neighbours alone:
/// their sum covers the part T_fluid = I - sum_w T_w of the moment tensor
/// -sum_j V_j x_ij (x) grad_i W_ij (the identity on a full lattice), each wall
/// holding T_w = -Z1 (r_iw + d1) n n^T normal to it and Z3 along it; so
/// grad P = T_fluid^-1 sum_j V_j (P_j - P_i) grad_i W_ij. (In 2D the z row is the identity.)
/// Falls back to the plain sum if T_fluid is near singular (a particle in a narrow gap).
Eigen::Vector3d renormalised_gradient(const Neighbourhood& n, std::span<const WallContact> contacts,
                                      const Eigen::Vector3d& fluid_gradient) {
  Eigen::Matrix3d fluid_moment = Eigen::Matrix3d::Identity();
  for (const WallContact& c : contacts) {
    const Eigen::Matrix3d normal_part = c.normal * c.normal.transpose();
    fluid_moment -= -c.values.z1 * (c.distance + c.values.depth1) * normal_part;
    fluid_moment -= c.values.z3 * (Eigen::Matrix3d::Identity() - normal_part);
  }
  if (n.model.dimension == 2) {
    fluid_moment.row(2).setZero();
    fluid_moment.col(2).setZero();
    fluid_moment(2, 2) = 1.0;
  }
  if (!(std::abs(fluid_moment.determinant()) > 0.05)) return fluid_gradient;
  return fluid_moment.inverse() * fluid_gradient;
}

}  // namespace

double wall_pressure_gradient(const FluidModel& model, const WallContact& contact, const Eigen::Vector3d& v_star,
                              double dt) {
  return model.density / dt * (v_star - contact.velocity).dot(contact.normal);
}

double laplacian_weight(const Kernel& kernel, const FluidModel& model, double r, double volume) {
  return 2.0 * volume * r * kernel.derivative(r) / (r * r + model.eta_squared());
}

std::vector<double> pressure_laplacian(const Neighbourhood& n, std::span<const double> mass,
                                       std::span<const double> density, std::span<const double> pressure) {
  std::vector<double> laplacian(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d&, double r) {
      const double volume = (mass[at(i)] + mass[at(j)]) / (density[at(i)] + density[at(j)]);
      sum += laplacian_weight(n.kernel, n.model, r, volume) * (pressure[at(i)] - pressure[at(j)]);
    });
    laplacian[at(i)] = sum;
  }
  return laplacian;
}

std::vector<double> kernel_density(const Neighbourhood& n, std::span<const double> mass) {
  std::vector<double> density(at(n.owned));
  const double self_weight = n.kernel.value(0.0);
  for (int i = 0; i < n.owned; ++i) {
    double sum = mass[at(i)] * self_weight;
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d&, double r) { sum += mass[at(j)] * n.kernel.value(r); });
    for (const WallContact& c : n.walls.of(i)) sum += n.model.density * c.values.z0;
    density[at(i)] = sum;
  }
  return density;
}

std::vector<double> position_divergence(const Neighbourhood& n, std::span<const double> mass,
                                        std::span<const double> density) {
  std::vector<double> divergence(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d&, double r) {
      sum -= mass[at(j)] / density[at(j)] * r * n.kernel.derivative(r);
    });
    for (const WallContact& c : n.walls.of(i))
      sum += -c.values.z1 * (c.distance + c.values.depth1) + (n.model.dimension - 1) * c.values.z3;
    divergence[at(i)] = sum;
  }
  return divergence;
}

std::vector<Eigen::Vector3d> viscous_acceleration(const Neighbourhood& n, std::span<const double> mass,
                                                  std::span<const double> density,
                                                  std::span<const Eigen::Vector3d> velocity,
                                                  std::vector<Eigen::Vector3d>& wall_force) {
  std::vector<Eigen::Vector3d> acceleration(at(n.owned), Eigen::Vector3d::Zero());
  const double mu = n.model.viscosity;
  if (mu == 0.0) return acceleration;
  const double eta2 = n.model.eta_squared();
  for (int i = 0; i < n.owned; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const double rho_i = density[at(i)];
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d&, double r) {
      // x_ij · grad_i W_ij = r W'(r)
      const double weight = mass[at(j)] * 2.0 * mu / (rho_i * density[at(j)]) * r * n.kernel.derivative(r) / (r * r + eta2);
      sum += weight * (velocity[at(i)] - velocity[at(j)]);
    });
    for (const WallContact& c : n.walls.of(i)) {
      const double extrapolation = 1.0 + c.values.depth2 / extrapolation_distance(n, c);
      const Eigen::Vector3d wall_part = 2.0 * mu / rho_i * c.values.z2 * extrapolation * (velocity[at(i)] - c.velocity);
      sum += wall_part;
      add_wall_force(n.wall_mesh, c, -mass[at(i)] * wall_part, wall_force);
    }
    acceleration[at(i)] = sum;
  }
  return acceleration;
}

std::vector<double> velocity_divergence(const Neighbourhood& n, std::span<const double> mass,
                                        std::span<const double> density, std::span<const Eigen::Vector3d> velocity) {
  std::vector<double> divergence(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    double sum = 0.0;
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d& x_ij, double r) {
      sum += mass[at(j)] * (velocity[at(i)] - velocity[at(j)]).dot(n.kernel.gradient(x_ij, r));
    });
    divergence[at(i)] = -sum / density[at(i)];
  }
  return divergence;
}

std::vector<Eigen::Vector3d> pressure_acceleration(const Neighbourhood& n, std::span<const double> mass,
                                                   std::span<const double> density, std::span<const double> pressure,
                                                   std::span<const Eigen::Vector3d> predicted_velocity, double dt,
                                                   std::vector<Eigen::Vector3d>& wall_force) {
  std::vector<Eigen::Vector3d> acceleration(at(n.owned));
  const double rho0 = n.model.density;
  for (int i = 0; i < n.owned; ++i) {
    const double rho_i = density[at(i)];
    const double p_i = pressure[at(i)] / (rho_i * rho_i);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d fluid_gradient = Eigen::Vector3d::Zero();  // sum_j V_j (P_j - P_i) grad_i W_ij
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d& x_ij, double r) {
      const double rho_j = density[at(j)];
      const Eigen::Vector3d grad = n.kernel.gradient(x_ij, r);
      sum -= mass[at(j)] * (p_i + pressure[at(j)] / (rho_j * rho_j)) * grad;
      fluid_gradient += mass[at(j)] / rho_j * (pressure[at(j)] - pressure[at(i)]) * grad;
    });
    const auto contacts = n.walls.of(i);
    const Eigen::Vector3d tangential_gradient =
        contacts.empty() ? Eigen::Vector3d::Zero() : renormalised_gradient(n, contacts, fluid_gradient);
    for (const WallContact& c : contacts) {
      const double wall_pressure = pressure[at(i)] - wall_pressure_gradient(n.model, c, predicted_velocity[at(i)], dt) *
                                                         (c.distance + c.values.depth1);
      const Eigen::Vector3d along_wall = tangential_gradient - tangential_gradient.dot(c.normal) * c.normal;
      const Eigen::Vector3d wall_part =
          -c.values.z1 * (rho0 * p_i + wall_pressure / rho0) * c.normal - c.values.z3 / rho0 * along_wall;
      sum += wall_part;
      add_wall_force(n.wall_mesh, c, -mass[at(i)] * wall_part, wall_force);
    }
    acceleration[at(i)] = sum;
  }
  return acceleration;
}

std::vector<Eigen::Vector3d> concentration_gradient(const Neighbourhood& n, std::span<const double> mass,
                                                    std::span<const double> density) {
  std::vector<Eigen::Vector3d> gradient(at(n.owned));
  for (int i = 0; i < n.owned; ++i) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d& x_ij, double r) {
      sum += mass[at(j)] / density[at(j)] * n.kernel.gradient(x_ij, r);
    });
    for (const WallContact& c : n.walls.of(i)) sum += c.values.z1 * c.normal;
    gradient[at(i)] = sum;
  }
  return gradient;
}

std::vector<Eigen::Vector3d> velocity_change_over_shift(const Neighbourhood& n, std::span<const double> mass,
                                                        std::span<const double> density,
                                                        std::span<const Eigen::Vector3d> velocity,
                                                        std::span<const Eigen::Vector3d> shift) {
  std::vector<Eigen::Vector3d> change(at(n.owned), Eigen::Vector3d::Zero());
  for (int i = 0; i < n.owned; ++i) {
    if (shift[at(i)].isZero()) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for_each_neighbour(n, i, [&](int j, const Eigen::Vector3d& x_ij, double r) {
      sum += mass[at(j)] / density[at(j)] * n.kernel.gradient(x_ij, r).dot(shift[at(i)]) *
             (velocity[at(j)] - velocity[at(i)]);
    });
    change[at(i)] = sum;
  }
  return change;
}

}  // namespace tankfsi::sph
