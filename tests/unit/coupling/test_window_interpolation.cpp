// Eqs 16-18 on their own: the window average of uneven sub-steps, the load
// ramp's end value and impulse for chi = 1 and 2, the wall's constant velocity.
#include <catch2/catch.hpp>

#include <vector>

#include "coupling/time/window_interpolation.hpp"

using namespace tankfsi::coupling;

TEST_CASE("eq 16: the window average is the impulse of the sub-steps over the window", "[coupling][time]") {
  WindowAverage average(2);
  // Sub-steps 0.3, 0.3, 0.3, 0.1 of a window of 1 (the last one shortened).
  const double steps[] = {0.3, 0.3, 0.3, 0.1};
  const double forces[][2] = {{1, -2}, {2, -4}, {3, -6}, {10, 0}};
  for (int k = 0; k < 4; ++k) average.add(forces[k], steps[k]);
  CHECK(average.duration() == Approx(1.0));
  const auto f = average.average(1.0);
  CHECK(f[0] == Approx(0.3 * (1 + 2 + 3) + 0.1 * 10));
  CHECK(f[1] == Approx(-0.3 * (2 + 4 + 6)));
  average.reset();
  CHECK(average.average(1.0)[0] == 0.0);
  CHECK_THROWS(average.add(std::vector<double>{1.0}, 0.1));
}

TEST_CASE("eq 17: chi = 1 reaches the average at the window end, chi = 2 keeps its impulse", "[coupling][time]") {
  const std::vector<double> start{10.0}, target{16.0};
  LoadRamp smooth(start);
  smooth.aim(target, 1.0);
  CHECK(smooth.end()[0] == 16.0);
  CHECK(smooth.at(0.5)[0] == 13.0);
  CHECK(smooth.mean()[0] == 13.0);  // half a window late: the impulse is 13, not 16

  LoadRamp conserving(start);
  conserving.aim(target, 2.0);
  CHECK(conserving.end()[0] == 22.0);
  CHECK(conserving.mean()[0] == 16.0);  // the window's impulse exactly
  // The next window starts from where this one ended: the zig-zag.
  conserving.next_window();
  conserving.aim(std::vector<double>{16.0}, 2.0);
  CHECK(conserving.start()[0] == 22.0);
  CHECK(conserving.end()[0] == 10.0);
  CHECK(conserving.mean()[0] == 16.0);
}

TEST_CASE("held window average: the load is the average over the whole window, in every window", "[coupling][time]") {
  LoadRamp held(std::vector<double>{10.0});
  held.hold(std::vector<double>{16.0});
  for (const double f : {0.0, 0.3, 1.0}) CHECK(held.at(f)[0] == 16.0);
  CHECK(held.mean()[0] == 16.0);
  held.next_window();
  held.hold(std::vector<double>{16.0});  // a steady force stays steady: no zig-zag
  CHECK(held.at(0.0)[0] == 16.0);
  CHECK(held.at(1.0)[0] == 16.0);
}

TEST_CASE("eq 18: the wall moves at constant velocity from its start to the target", "[coupling][time]") {
  DisplacementPath path(std::vector<double>{0.0, 1.0, 2.0});
  path.aim({0.5, 1.0, 1.0});
  CHECK(path.at(0.4) == std::vector<double>{0.2, 1.0, 1.6});
  const auto velocity = path.velocity(0.01);
  CHECK(velocity[0] == Approx(50.0));
  CHECK(velocity[1] == 0.0);
  CHECK(velocity[2] == Approx(-100.0));
  path.next_window();
  CHECK(path.start() == std::vector<double>{0.5, 1.0, 1.0});
}
