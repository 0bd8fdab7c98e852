#include "sph_solver/isph/fluid_model.hpp"

#include <cmath>

namespace tankfsi::sph {

double FluidModel::particle_mass() const { return density * std::pow(spacing, dimension); }

Eigen::Vector3d FluidModel::body_force(const Eigen::Vector3d& ground_acceleration) const {
  Eigen::Vector3d ground = ground_acceleration;
  if (dimension == 2) ground = Eigen::Vector3d(ground_acceleration.x(), ground_acceleration.z(), 0.0);
  return -gravity * up() - ground;
}

}  // namespace tankfsi::sph
