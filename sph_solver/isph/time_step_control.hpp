#pragma once
// Time-step limits of the ISPH step (METHOD.md §1 step 4):
//   CFL          C h / |v|max
//   viscous      0.125 h^2 / nu
//   body force   0.25 sqrt(h / |F|)
// and the largest step the user allows. A fixed step (the paper's 0.5 ms in 2D,
// 1 ms in 3D) is checked against the same limits every step: a breach is an error,
// not a silent instability.
#include <string>

#include "sph_solver/isph/fluid_model.hpp"

namespace tankfsi::sph {

struct TimeStepLimits {
  double cfl = 0.0;
  double viscous = 0.0;
  double body_force = 0.0;
  double maximum = 0.0;

  /// The smallest limit and its name ("cfl", "viscous", "body_force", "maximum").
  [[nodiscard]] double smallest() const;
  [[nodiscard]] std::string limiting() const;
};

/// Limits for the fastest particle speed and the body-force magnitude.
/// `cfl_number` is C; `maximum` the user's upper bound (infinity for none).
[[nodiscard]] TimeStepLimits time_step_limits(const FluidModel& model, double cfl_number, double maximum,
                                              double max_speed, double body_force);

}  // namespace tankfsi::sph
