// The standing wave's initial velocity (standing_wave.hpp) against the linear
// sloshing solution it stands for: Faltinsen's frequency for the paper's tank, a
// divergence-free field (central differences of the velocity itself), no flow
// through the floor and the side walls, and a surface velocity d eta/dt = a omega
// cos(k x) at t = 0.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "sph_solver/particles/standing_wave.hpp"

using namespace tankfsi::sph;
using Eigen::Vector3d;

namespace {

StandingWave paper_tank() {
  StandingWave w;
  w.x0 = 0.0;
  w.width = 2.0;
  w.floor = 0.0;
  w.depth = 0.69;
  w.mode = 1;
  w.amplitude = 0.01;
  return w;
}

}  // namespace

TEST_CASE("standing wave: Faltinsen's first period of the paper's tank", "[standing_wave]") {
  // omega^2 = g (pi/L) tanh(pi h / L), L = 2.00 m, h = 0.69 m: T1 = 1.796 s (VALIDATION.md).
  const StandingWave w = paper_tank();
  CHECK(2.0 * std::numbers::pi / w.frequency() == Approx(1.796).margin(5e-4));
  StandingWave second = w;
  second.mode = 2;
  CHECK(second.wave_number() == Approx(std::numbers::pi));
}

TEST_CASE("standing wave: divergence-free, tangential on the walls, the surface rises at a omega", "[standing_wave]") {
  StandingWave w = paper_tank();
  w.x0 = 0.3;  // an offset tank: the phases follow the wall at x0
  w.floor = -0.1;
  const double step = 1e-6;
  double worst_divergence = 0.0, scale = 0.0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 10; ++j) {
      const Vector3d x(w.x0 + w.width * i / 20.0, w.floor + w.depth * j / 10.0, 0.0);
      const double divergence =
          (w.velocity(x + Vector3d(step, 0, 0)).x() - w.velocity(x - Vector3d(step, 0, 0)).x() +
           w.velocity(x + Vector3d(0, step, 0)).y() - w.velocity(x - Vector3d(0, step, 0)).y()) / (2.0 * step);
      worst_divergence = std::max(worst_divergence, std::abs(divergence));
      scale = std::max(scale, w.velocity(x).norm() * w.wave_number());
    }
  // Central differences: round-off ~1e-10 / 1e-6 relative to |u| k ~ 0.06 1/s.
  CHECK(worst_divergence < 1e-6 * scale);
  for (int i = 0; i <= 10; ++i) {
    const double y = w.floor + w.depth * i / 10.0;
    CHECK(std::abs(w.velocity(Vector3d(w.x0, y, 0)).x()) < 1e-15);
    CHECK(std::abs(w.velocity(Vector3d(w.x0 + w.width, y, 0)).x()) < 1e-15);
    const double x = w.x0 + w.width * i / 10.0;
    CHECK(std::abs(w.velocity(Vector3d(x, w.floor, 0)).y()) < 1e-15);
    const double rise = w.amplitude * w.frequency() * std::cos(w.wave_number() * (x - w.x0));
    CHECK(w.velocity(Vector3d(x, w.floor + w.depth, 0)).y() == Approx(rise).margin(1e-12));
  }
}

TEST_CASE("standing wave: applied to particles, bad parameters refused", "[standing_wave]") {
  Particles p;
  p.push_back(0, Vector3d(0.5, 0.6, 0), Vector3d::Zero(), 0.4, 0.0);
  const StandingWave w = paper_tank();
  apply_standing_wave(w, p);
  CHECK((p.velocity[0] - w.velocity(p.position[0])).norm() == 0.0);
  for (auto broken : {&StandingWave::width, &StandingWave::depth, &StandingWave::gravity}) {
    StandingWave bad = w;
    bad.*broken = 0.0;
    CHECK_THROWS_AS(apply_standing_wave(bad, p), std::invalid_argument);
  }
  StandingWave bad = w;
  bad.mode = 0;
  CHECK_THROWS_AS(apply_standing_wave(bad, p), std::invalid_argument);
  bad = w;
  bad.amplitude = std::nan("");
  CHECK_THROWS_AS(apply_standing_wave(bad, p), std::invalid_argument);
}
