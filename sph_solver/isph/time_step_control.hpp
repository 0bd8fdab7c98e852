#pragma once
// Time-step limits of the ISPH step (METHOD.md §1 step 4):
//   CFL          C h / |v|max
//   viscous      0.125 h^2 / nu
//   body force   0.25 sqrt(h / |F|)
//   pressure     0.5 h / sqrt(|P|max / rho0)
// and the largest step the user allows. A fixed step (the paper's 0.5 ms in 2D,
// 1 ms in 3D) is checked against the same limits every step: a breach is an error,
// not a silent instability.
//
// The pressure limit: the pair forces of eq 4 at a given pressure stiffen like
// springs of rate ~ (P / rho0) / h^2 as particles approach, and the step moves the
// particles explicitly under them. Measured on the 2D tank at rest (quintic spline,
// h = 1.2 L0), the step turns unstable at dt sqrt(P/rho0) / h = 0.8 to 1.1 whatever
// the body force: L0 = 0.02 m, H = 0.70 m: 7 ms grows slowly, 10 ms at once;
// H = 0.36 m: 10.5 ms (coefficient 0.82) stays settled; L0 = 0.01 m, H = 0.70 m:
// 4 ms settled (0.88), 5 ms unstable (1.1) — all inside the body-force limit
// (12.4 and 8.7 ms). 0.5 keeps a margin of 1.6 to that threshold.
#include <string>

#include "sph_solver/isph/fluid_model.hpp"

namespace tankfsi::sph {

struct TimeStepLimits {
  double cfl = 0.0;
  double viscous = 0.0;
  double body_force = 0.0;
  double pressure = 0.0;
  double maximum = 0.0;

  /// The smallest limit and its name ("cfl", "viscous", "body_force", "pressure",
  /// "maximum").
  [[nodiscard]] double smallest() const;
  [[nodiscard]] std::string limiting() const;
};

/// Coefficient of the pressure limit (see above).
inline constexpr double pressure_step_coefficient = 0.5;

/// Limits for the fastest particle speed, the body-force magnitude and the largest
/// |P|. `cfl_number` is C; `maximum` the user's upper bound (infinity for none).
[[nodiscard]] TimeStepLimits time_step_limits(const FluidModel& model, double cfl_number, double maximum,
                                              double max_speed, double body_force, double max_pressure);

/// The Courant number |v|max dt / h a step of dt reached, with the largest
/// speed at its end.
[[nodiscard]] double realised_courant(const FluidModel& model, double max_speed, double dt);

}  // namespace tankfsi::sph
