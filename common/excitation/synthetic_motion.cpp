#include "common/excitation/synthetic_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace tankfsi {

namespace {

constexpr double sample_rate = 100.0;          // Hz
constexpr double lowest_frequency = 0.05;      // Hz
constexpr double highest_frequency = 25.0;     // Hz
constexpr double final_envelope_value = 0.05;  // e(duration)
constexpr double two_pi = 2.0 * std::numbers::pi;

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("synthetic ground motion: " + message);
}

void validate(const SyntheticMotionParameters& p) {
  auto finite = [](double v) { return std::isfinite(v); };
  require(finite(p.peak_acceleration) && p.peak_acceleration > 0.0, "peak acceleration must be positive");
  require(finite(p.dominant_period) && p.dominant_period > 0.0, "dominant period must be positive");
  require(finite(p.ground_damping) && p.ground_damping > 0.0 && p.ground_damping < 1.0,
          "ground damping must lie in (0, 1)");
  require(finite(p.rise_time) && p.rise_time > 0.0, "rise time must be positive");
  require(finite(p.strong_duration) && p.strong_duration >= 0.0, "strong duration must not be negative");
  require(finite(p.duration) && p.duration > p.rise_time + p.strong_duration,
          "duration must be longer than rise time + strong duration");
  require(p.component_ratios.allFinite() && (p.component_ratios.array() >= 0.0).all(),
          "component ratios must not be negative");
}

// Uniform in [0, 1) from the top 53 bits: the same on every platform.
double unit_uniform(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }

// Frequency grid of the spectral representation (see the header for the choice of N).
struct FrequencyGrid {
  std::size_t count = 0;
  double lowest_omega = 0.0;  // rad/s, lower edge of the first band
  double delta_omega = 0.0;   // rad/s
  [[nodiscard]] double omega(std::size_t k) const {
    return lowest_omega + (static_cast<double>(k) + 0.5) * delta_omega;
  }
};

FrequencyGrid frequency_grid(const SyntheticMotionParameters& p) {
  const double band = highest_frequency - lowest_frequency;
  const double dominant_frequency = 1.0 / p.dominant_period;
  const double widest_step = std::min(1.0 / (2.0 * p.duration), p.ground_damping * dominant_frequency / 5.0);
  const auto count = static_cast<std::size_t>(std::ceil(band / widest_step));
  return FrequencyGrid{count, two_pi * lowest_frequency, two_pi * band / static_cast<double>(count)};
}

// One stationary component sum_k A_k cos(w_k t_n + phi_k) at t_n = n / sample_rate.
// cos(w t_n + phi) is advanced from sample to sample by a complex rotation
// e^{i w dt} instead of calling cos for each of the ~10^7-10^8 terms; the
// rounding error grows like n * 1e-16 relative, below 1e-11 for an hour of samples.
std::vector<double> stationary_component(const FrequencyGrid& grid, const std::vector<double>& amplitudes,
                                         const std::vector<double>& phases, std::size_t samples) {
  const double dt = 1.0 / sample_rate;
  std::vector<double> re(grid.count), im(grid.count), step_re(grid.count), step_im(grid.count);
  for (std::size_t k = 0; k < grid.count; ++k) {
    re[k] = amplitudes[k] * std::cos(phases[k]);
    im[k] = amplitudes[k] * std::sin(phases[k]);
    step_re[k] = std::cos(grid.omega(k) * dt);
    step_im[k] = std::sin(grid.omega(k) * dt);
  }
  std::vector<double> out(samples);
  for (std::size_t n = 0; n < samples; ++n) {
    double sum = 0.0;
    for (std::size_t k = 0; k < grid.count; ++k) {
      sum += re[k];
      const double next_re = re[k] * step_re[k] - im[k] * step_im[k];
      im[k] = re[k] * step_im[k] + im[k] * step_re[k];
      re[k] = next_re;
    }
    out[n] = sum;
  }
  return out;
}

}  // namespace

double kanai_tajimi_spectrum(double omega, double omega_g, double zeta_g) {
  const double wg2 = omega_g * omega_g;
  const double w2 = omega * omega;
  const double damping_term = 4.0 * zeta_g * zeta_g * wg2 * w2;
  return (wg2 * wg2 + damping_term) / ((wg2 - w2) * (wg2 - w2) + damping_term);
}

double synthetic_envelope(double t, const SyntheticMotionParameters& p) {
  if (t < p.rise_time) return (t / p.rise_time) * (t / p.rise_time);
  const double strong_end = p.rise_time + p.strong_duration;
  if (t <= strong_end) return 1.0;
  const double decay_rate = -std::log(final_envelope_value) / (p.duration - strong_end);
  return std::exp(-decay_rate * (t - strong_end));
}

SampledGroundMotion make_synthetic_motion(const SyntheticMotionParameters& p) {
  validate(p);
  const FrequencyGrid grid = frequency_grid(p);
  const double omega_g = two_pi / p.dominant_period;
  std::vector<double> amplitudes(grid.count);
  for (std::size_t k = 0; k < grid.count; ++k)
    amplitudes[k] = std::sqrt(2.0 * kanai_tajimi_spectrum(grid.omega(k), omega_g, p.ground_damping) *
                              grid.delta_omega);

  const auto samples = static_cast<std::size_t>(std::llround(p.duration * sample_rate)) + 1;
  std::vector<double> times(samples), envelope(samples);
  for (std::size_t n = 0; n < samples; ++n) {
    times[n] = static_cast<double>(n) / sample_rate;
    envelope[n] = synthetic_envelope(times[n], p);
  }

  // Phases of x, then y, then z from one engine: independent components.
  std::mt19937_64 engine(p.seed);
  std::vector<Eigen::Vector3d> accelerations(samples, Eigen::Vector3d::Zero());
  for (int c = 0; c < 3; ++c) {
    std::vector<double> phases(grid.count);
    for (double& phi : phases) phi = two_pi * unit_uniform(engine);
    std::vector<double> component = stationary_component(grid, amplitudes, phases, samples);
    double peak = 0.0;
    for (std::size_t n = 0; n < samples; ++n) {
      component[n] *= envelope[n];
      peak = std::max(peak, std::abs(component[n]));
    }
    // (a / peak) * target: the sample at the peak becomes exactly +-target.
    const double target = p.component_ratios[c] * p.peak_acceleration;
    for (std::size_t n = 0; n < samples; ++n)
      accelerations[n][c] = peak > 0.0 ? component[n] / peak * target : 0.0;
  }
  return SampledGroundMotion(std::move(times), std::move(accelerations));
}

}  // namespace tankfsi
