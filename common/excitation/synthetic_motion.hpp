#pragma once
// Synthetic ground motion: a stationary Gaussian-like process with the
// Kanai-Tajimi spectrum, simulated by the spectral representation method and
// shaped by a Saragoni/Jennings-type envelope.
//   K. Kanai (1957), Semi-empirical formula for the seismic characteristics of
//     the ground, Bull. Earthquake Res. Inst. Univ. Tokyo 35, 309-325.
//   H. Tajimi (1960), A statistical method of determining the maximum response
//     of a building structure during an earthquake, Proc. 2nd WCEE, Tokyo.
//   M. Shinozuka, G. Deodatis (1991), Simulation of stochastic processes by
//     spectral representation, Appl. Mech. Rev. 44(4), 191-204.
//   P. C. Jennings, G. W. Housner, N. C. Tsai (1968), Simulated earthquake
//     motions, EERL report, Caltech (the rise/strong/decay envelope).
//
// The same parameters and seed give bit-for-bit the same samples on every rank
// and every run of the same build: phases come from std::mt19937_64, whose
// output the C++ standard fixes, mapped to [0, 2 pi) here rather than through
// std::uniform_real_distribution, whose output is implementation-defined.
#include <Eigen/Core>

#include <cstdint>

#include "common/excitation/ground_motion.hpp"

namespace tankfsi {

struct SyntheticMotionParameters {
  std::uint64_t seed = 1;          ///< equal seeds give equal motions
  double peak_acceleration = 1.0;  ///< m/s^2, max |a_x| of the result
  /// s, 2 pi / omega_g: period of the ground filter, near where the spectrum peaks
  /// (the Kanai-Tajimi peak lies at omega_g ((sqrt(1 + 8 zeta^2) - 1) / (4 zeta^2))^(1/2),
  /// 0.965 omega_g for zeta_g = 0.2).
  double dominant_period = 6.0;
  double ground_damping = 0.2;  ///< zeta_g in (0, 1): bandwidth of the ground filter
  double duration = 60.0;       ///< s, length of the motion; > rise_time + strong_duration
  double rise_time = 5.0;       ///< s, envelope (t / rise_time)^2 before
  double strong_duration = 20.0;  ///< s, envelope 1 after the rise, then exponential decay
  /// Peaks of x, y, z relative to x's; each component has its own phases and is
  /// normalised to its own peak, then multiplied by ratio * peak_acceleration.
  Eigen::Vector3d component_ratios{1.0, 0.7, 0.5};
};

/// Kanai-Tajimi spectral shape S(w) = (wg^4 + 4 zg^2 wg^2 w^2) / ((wg^2 - w^2)^2 + 4 zg^2 wg^2 w^2):
/// white noise at bedrock filtered by a soil layer modelled as one damped
/// oscillator. Normalised to S(0) = 1; the intensity S0 is left out because the
/// motion is scaled to its peak afterwards.
[[nodiscard]] double kanai_tajimi_spectrum(double omega, double omega_g, double zeta_g);

/// Envelope e(t): (t / rise)^2 for t < rise, 1 until rise + strong, then
/// exp(-c (t - rise - strong)) with c such that e(duration) = 0.05.
[[nodiscard]] double synthetic_envelope(double t, const SyntheticMotionParameters& parameters);

/// a(t_n) = e(t_n) sum_k sqrt(2 S(w_k) dw) cos(w_k t_n + phi_k), sampled at
/// t_n = n / 100 s over [0, duration], then scaled to the peaks (see above).
/// Frequencies w_k: midpoints of N equal bands covering 0.05-25 Hz, the band
/// of engineering interest (sloshing at 0.1-0.5 Hz, tank shell modes at 2-10 Hz),
/// well below the 50 Hz Nyquist frequency of the samples. N is the smallest
/// number with band width df <= 1/(2 duration), so the sum, periodic with
/// period 1/df, does not repeat within the motion, and df <= zeta_g f_g / 5,
/// i.e. at least 10 bands across the spectrum's half-power width ~2 zeta_g f_g
/// (N = 3743 for the defaults: 60 s, 6 s, zeta_g 0.2).
/// Throws std::invalid_argument for parameters out of range.
[[nodiscard]] SampledGroundMotion make_synthetic_motion(const SyntheticMotionParameters& parameters);

}  // namespace tankfsi
