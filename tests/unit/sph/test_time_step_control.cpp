// The time-step limits (time_step_control.hpp) against their formulas for the 2D
// tank of the hydrostatic case (L0 = 0.02 m, h = 0.024 m, water), and which limit
// is named: the CFL limit for a fast flow, the pressure limit for a deep tank at
// rest (0.5 h / sqrt(rho g H / rho0) = 4.58 ms for H = 0.70 m, below the body-force
// limit 0.25 sqrt(h / g) = 12.4 ms, where the step was measured to turn unstable).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "sph_solver/isph/time_step_control.hpp"
#include "still_tank.hpp"

using namespace tankfsi::sph;
using tankfsi::test::water;


TEST_CASE("time-step limits and the limit that binds", "[time_step]") {
  const FluidModel m = water();
  constexpr double infinity = std::numeric_limits<double>::infinity();
  const double bottom = 1000.0 * 9.81 * 0.70;
  const TimeStepLimits rest = time_step_limits(m, 0.2, 0.002 * 10, 0.0, 9.81, bottom);
  CHECK(rest.cfl == infinity);
  CHECK(rest.viscous == Approx(0.125 * 0.024 * 0.024 / 1e-6));
  CHECK(rest.body_force == Approx(0.25 * std::sqrt(0.024 / 9.81)));
  CHECK(rest.pressure == Approx(0.5 * 0.024 / std::sqrt(bottom / 1000.0)));
  CHECK(rest.pressure == Approx(4.58e-3).epsilon(1e-3));
  CHECK(rest.smallest() == rest.pressure);
  CHECK(rest.limiting() == "pressure");
  // Negative pressures count by their size.
  CHECK(time_step_limits(m, 0.2, 1.0, 0.0, 9.81, -bottom).pressure == rest.pressure);
  const TimeStepLimits fast = time_step_limits(m, 0.2, 1.0, 6.0, 9.81, bottom);
  CHECK(fast.cfl == Approx(0.2 * 0.024 / 6.0));
  CHECK(fast.limiting() == "cfl");
  const TimeStepLimits capped = time_step_limits(m, 0.2, 1e-3, 0.0, 9.81, 0.0);
  CHECK(capped.pressure == infinity);
  CHECK(capped.limiting() == "maximum");
  CHECK(time_step_limits(m, 0.2, infinity, 0.0, 0.0, 0.0).limiting() == "viscous");
}
