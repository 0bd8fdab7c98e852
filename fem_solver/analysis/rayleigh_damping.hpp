#pragma once
// Rayleigh damping C = alpha M + beta K from two target modes (METHOD.md eq 9,
// corrected): 2 zeta_i omega_i = alpha + beta omega_i^2 at i = 1, 2.
namespace tankfsi::fem {

struct RayleighCoefficients {
  double alpha = 0.0;  ///< 1/s, mass-proportional
  double beta = 0.0;   ///< s, stiffness-proportional

  /// The damping ratio this C gives a mode of circular frequency omega.
  [[nodiscard]] double ratio_at(double omega) const { return 0.5 * (alpha / omega + beta * omega); }
};

/// Solves the 2x2 system of eq 9 for two distinct circular frequencies
/// (rad/s); throws std::invalid_argument when they coincide to 1e-9 or one
/// is not positive.
[[nodiscard]] RayleighCoefficients rayleigh_from_modes(double omega_1, double zeta_1, double omega_2, double zeta_2);

}  // namespace tankfsi::fem
