#include "fem_solver/analysis/rayleigh_damping.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tankfsi::fem {

RayleighCoefficients rayleigh_from_modes(double omega_1, double zeta_1, double omega_2, double zeta_2) {
  if (!(omega_1 > 0.0 && omega_2 > 0.0))
    throw std::invalid_argument("Rayleigh damping needs two positive target frequencies");
  if (std::abs(omega_2 - omega_1) <= 1e-9 * std::max(omega_1, omega_2))
    throw std::invalid_argument("the two Rayleigh target modes have the same frequency (" + std::to_string(omega_1) +
                                " rad/s): choose modes of different frequency");
  // [1 w1^2; 1 w2^2] [alpha; beta] = [2 z1 w1; 2 z2 w2]
  const double determinant = omega_2 * omega_2 - omega_1 * omega_1;
  RayleighCoefficients c;
  c.beta = (2.0 * zeta_2 * omega_2 - 2.0 * zeta_1 * omega_1) / determinant;
  c.alpha = 2.0 * zeta_1 * omega_1 - c.beta * omega_1 * omega_1;
  return c;
}

}  // namespace tankfsi::fem
