#pragma once
// GroundMotion: the ground acceleration a_g(t) in the tank-base frame (m/s^2,
// components x, y, z) as a function of simulation time t (s).
//
// Kinds: a sampled series (K-NET, CSV or synthetic records), a harmonic motion
// and a linear sine sweep; DelayedGroundMotion shifts any of them to start at
// a later simulation time, so the start time is handled in one place.
#include <Eigen/Core>

#include <memory>
#include <vector>

namespace tankfsi {

class GroundMotion {
 public:
  virtual ~GroundMotion() = default;
  /// Ground acceleration at simulation time t (m/s^2).
  [[nodiscard]] virtual Eigen::Vector3d acceleration(double t) const = 0;
  /// Time after which the motion is zero for good (s); infinity if it never stops.
  [[nodiscard]] virtual double duration() const = 0;
};

/// The ground at rest: excitation.type none.
class ZeroGroundMotion final : public GroundMotion {
 public:
  [[nodiscard]] Eigen::Vector3d acceleration(double) const override { return Eigen::Vector3d::Zero(); }
  [[nodiscard]] double duration() const override { return 0.0; }
};

/// A 3-component series at strictly increasing times (uniform or not),
/// linearly interpolated between samples and zero outside [first, last] time.
class SampledGroundMotion final : public GroundMotion {
 public:
  /// Throws std::invalid_argument unless the sizes match, there is at least one
  /// sample, times strictly increase and every number is finite.
  SampledGroundMotion(std::vector<double> times, std::vector<Eigen::Vector3d> accelerations);

  [[nodiscard]] Eigen::Vector3d acceleration(double t) const override;
  [[nodiscard]] double duration() const override { return times_.back(); }

  [[nodiscard]] const std::vector<double>& times() const { return times_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& accelerations() const { return accelerations_; }

 private:
  std::vector<double> times_;
  std::vector<Eigen::Vector3d> accelerations_;
};

/// How a recorded series becomes a simulation input: the part [window_start,
/// window_end] of the record (record time) is kept, and a sample at record time
/// t_r appears at t = (t_r - window_start) * time_scale with its acceleration
/// times amplitude_scale. The window ends are interpolated, so the kept series
/// starts exactly at t = 0 even when window_start falls between samples.
struct RecordMapping {
  double window_start = 0.0;  ///< s, record time; within the record
  double window_end = 0.0;    ///< s, record time; >= window_start, within the record
  double time_scale = 1.0;    ///< > 0; 0.5 plays the record twice as fast
  double amplitude_scale = 1.0;
};

/// The whole record as the window, with unit scales.
[[nodiscard]] RecordMapping whole_record(const SampledGroundMotion& record);

/// Applies a mapping; throws std::invalid_argument if the window ends before it
/// starts or leaves the record, or a scale is not positive (time) / negative (amplitude).
[[nodiscard]] SampledGroundMotion map_record(const SampledGroundMotion& record, const RecordMapping& mapping);

/// Any motion started at simulation time start_time instead of 0: zero before,
/// inner(t - start_time) after. Lets the liquid settle before the ground moves.
class DelayedGroundMotion final : public GroundMotion {
 public:
  DelayedGroundMotion(std::unique_ptr<GroundMotion> inner, double start_time);

  [[nodiscard]] Eigen::Vector3d acceleration(double t) const override;
  [[nodiscard]] double duration() const override { return start_time_ + inner_->duration(); }

 private:
  std::unique_ptr<GroundMotion> inner_;
  double start_time_;
};

/// A sine of amplitude a along the unit vector d, a(t) = w(t) a d sin(phase(t)),
/// zero before t = 0 and after duration(). w is a half-cosine taper,
/// w = (1 - cos(pi t / ramp)) / 2 for t < ramp and 1 after, so that both the
/// acceleration and its rate start from zero instead of jumping.
class TaperedSineGroundMotion : public GroundMotion {
 public:
  [[nodiscard]] Eigen::Vector3d acceleration(double t) const final;

 protected:
  /// direction is normalised here; throws std::invalid_argument if it is zero,
  /// the amplitude or ramp duration is negative, or a number is not finite.
  TaperedSineGroundMotion(const Eigen::Vector3d& direction, double amplitude, double ramp_duration);
  /// Phase of the sine at time t >= 0 (rad).
  [[nodiscard]] virtual double phase(double t) const = 0;

 private:
  Eigen::Vector3d direction_;
  double amplitude_;
  double ramp_duration_;
};

/// a(t) = w(t) a d sin(2 pi f t): steady harmonic shaking, never stops.
class HarmonicGroundMotion final : public TaperedSineGroundMotion {
 public:
  HarmonicGroundMotion(const Eigen::Vector3d& direction, double amplitude, double frequency,
                       double ramp_duration);
  [[nodiscard]] double duration() const override;

 private:
  [[nodiscard]] double phase(double t) const override;
  double frequency_;
};

/// Linear sine sweep from f0 to f1 over sweep_duration T: phase
/// 2 pi (f0 t + (f1 - f0) t^2 / (2 T)), so the instantaneous frequency
/// f0 + (f1 - f0) t / T passes every sloshing and shell mode in the band once.
/// Zero after T.
class SweepGroundMotion final : public TaperedSineGroundMotion {
 public:
  SweepGroundMotion(const Eigen::Vector3d& direction, double amplitude, double start_frequency,
                    double end_frequency, double sweep_duration, double ramp_duration);
  [[nodiscard]] double duration() const override { return sweep_duration_; }

 private:
  [[nodiscard]] double phase(double t) const override;
  double start_frequency_;
  double end_frequency_;
  double sweep_duration_;
};

}  // namespace tankfsi
