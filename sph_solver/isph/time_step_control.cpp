#include "sph_solver/isph/time_step_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tankfsi::sph {

TimeStepLimits time_step_limits(const FluidModel& model, double cfl_number, double maximum, double max_speed,
                                double body_force, double max_pressure) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  const double h = model.smoothing_length;
  const double kinematic_viscosity = model.viscosity / model.density;
  TimeStepLimits limits;
  limits.cfl = max_speed > 0.0 ? cfl_number * h / max_speed : infinity;
  limits.viscous = kinematic_viscosity > 0.0 ? 0.125 * h * h / kinematic_viscosity : infinity;
  limits.body_force = body_force > 0.0 ? 0.25 * std::sqrt(h / body_force) : infinity;
  const double pressure_speed = std::sqrt(std::abs(max_pressure) / model.density);
  limits.pressure = pressure_speed > 0.0 ? pressure_step_coefficient * h / pressure_speed : infinity;
  limits.maximum = maximum;
  return limits;
}

double TimeStepLimits::smallest() const { return std::min({cfl, viscous, body_force, pressure, maximum}); }

std::string TimeStepLimits::limiting() const {
  const double s = smallest();
  if (s == cfl) return "cfl";
  if (s == viscous) return "viscous";
  if (s == body_force) return "body_force";
  if (s == pressure) return "pressure";
  return "maximum";
}

double realised_courant(const FluidModel& model, double max_speed, double dt) {
  return max_speed * dt / model.smoothing_length;
}

}  // namespace tankfsi::sph
