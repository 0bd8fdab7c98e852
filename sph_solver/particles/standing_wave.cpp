#include "sph_solver/particles/standing_wave.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tankfsi::sph {

double StandingWave::wave_number() const { return mode * std::numbers::pi / width; }

double StandingWave::frequency() const {
  const double k = wave_number();
  return std::sqrt(gravity * k * std::tanh(k * depth));
}

Eigen::Vector3d StandingWave::velocity(const Eigen::Vector3d& x) const {
  const double k = wave_number();
  const double scale = amplitude * frequency() / std::sinh(k * depth);
  const double kx = k * (x.x() - x0);
  const double ky = k * (x.y() - floor);
  return {-scale * std::sin(kx) * std::cosh(ky), scale * std::cos(kx) * std::sinh(ky), 0.0};
}

void apply_standing_wave(const StandingWave& wave, Particles& particles) {
  if (!(wave.width > 0.0) || !(wave.depth > 0.0) || !(wave.gravity > 0.0) || wave.mode < 1 ||
      !std::isfinite(wave.amplitude) || !std::isfinite(wave.x0) || !std::isfinite(wave.floor))
    throw std::invalid_argument("standing wave: width, depth and gravity must be positive, the mode >= 1");
  for (std::size_t i = 0; i < particles.size(); ++i) particles.velocity[i] = wave.velocity(particles.position[i]);
}

}  // namespace tankfsi::sph
