#include "common/excitation/ground_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tankfsi {

namespace {

void require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument(message);
}

// Linear interpolation of a record known to cover t (times[0] <= t <= times.back()).
// At a sample time the weight is exactly 0, so samples are returned unchanged.
Eigen::Vector3d interpolate(const std::vector<double>& times, const std::vector<Eigen::Vector3d>& values,
                            double t) {
  const auto upper = std::upper_bound(times.begin(), times.end(), t);
  if (upper == times.end()) return values.back();  // t == last time
  const auto i = static_cast<std::size_t>(upper - times.begin()) - 1;
  const double weight = (t - times[i]) / (times[i + 1] - times[i]);
  return values[i] + weight * (values[i + 1] - values[i]);
}

}  // namespace

// ---- SampledGroundMotion ------------------------------------------------------------------

SampledGroundMotion::SampledGroundMotion(std::vector<double> times, std::vector<Eigen::Vector3d> accelerations)
    : times_(std::move(times)), accelerations_(std::move(accelerations)) {
  require(!times_.empty(), "a sampled ground motion needs at least one sample");
  require(times_.size() == accelerations_.size(),
          "a sampled ground motion needs as many accelerations as times (" + std::to_string(times_.size()) +
              " times, " + std::to_string(accelerations_.size()) + " accelerations)");
  for (std::size_t i = 0; i < times_.size(); ++i) {
    require(std::isfinite(times_[i]) && accelerations_[i].allFinite(),
            "sample " + std::to_string(i) + " of a ground motion is not finite");
    require(i == 0 || times_[i] > times_[i - 1],
            "times of a ground motion must strictly increase (sample " + std::to_string(i) + ")");
  }
}

Eigen::Vector3d SampledGroundMotion::acceleration(double t) const {
  if (!(t >= times_.front() && t <= times_.back())) return Eigen::Vector3d::Zero();
  return interpolate(times_, accelerations_, t);
}

// ---- record windows and scales -----------------------------------------------------------

RecordMapping whole_record(const SampledGroundMotion& record) {
  return RecordMapping{record.times().front(), record.times().back(), 1.0, 1.0};
}

SampledGroundMotion map_record(const SampledGroundMotion& record, const RecordMapping& mapping) {
  const auto& times = record.times();
  const auto& values = record.accelerations();
  require(mapping.window_start >= times.front() && mapping.window_end <= times.back(),
          "window [" + std::to_string(mapping.window_start) + ", " + std::to_string(mapping.window_end) +
              "] s leaves the record [" + std::to_string(times.front()) + ", " + std::to_string(times.back()) +
              "] s");
  require(mapping.window_end >= mapping.window_start, "window end must not be before window start");
  require(mapping.time_scale > 0.0 && std::isfinite(mapping.time_scale), "time scale must be positive");
  require(mapping.amplitude_scale >= 0.0 && std::isfinite(mapping.amplitude_scale),
          "amplitude scale must not be negative");

  // Both window ends are samples of the result (interpolated unless they fall on
  // a sample), followed or preceded by the record's samples strictly inside.
  std::vector<double> record_times{mapping.window_start};
  const auto first_inside = std::upper_bound(times.begin(), times.end(), mapping.window_start);
  const auto end_inside = std::lower_bound(first_inside, times.end(), mapping.window_end);
  record_times.insert(record_times.end(), first_inside, end_inside);
  if (mapping.window_end > mapping.window_start) record_times.push_back(mapping.window_end);

  std::vector<double> mapped_times;
  std::vector<Eigen::Vector3d> mapped_values;
  mapped_times.reserve(record_times.size());
  mapped_values.reserve(record_times.size());
  for (const double t : record_times) {
    mapped_times.push_back((t - mapping.window_start) * mapping.time_scale);
    mapped_values.push_back(mapping.amplitude_scale * interpolate(times, values, t));
  }
  return SampledGroundMotion(std::move(mapped_times), std::move(mapped_values));
}

// ---- DelayedGroundMotion ------------------------------------------------------------------

DelayedGroundMotion::DelayedGroundMotion(std::unique_ptr<GroundMotion> inner, double start_time)
    : inner_(std::move(inner)), start_time_(start_time) {
  require(inner_ != nullptr, "a delayed ground motion needs a motion to delay");
  require(std::isfinite(start_time_) && start_time_ >= 0.0, "start time must be finite and not negative");
}

Eigen::Vector3d DelayedGroundMotion::acceleration(double t) const {
  if (t < start_time_) return Eigen::Vector3d::Zero();
  return inner_->acceleration(t - start_time_);
}

// ---- tapered sines ---------------------------------------------------------------------------

TaperedSineGroundMotion::TaperedSineGroundMotion(const Eigen::Vector3d& direction, double amplitude,
                                                 double ramp_duration)
    : direction_(direction), amplitude_(amplitude), ramp_duration_(ramp_duration) {
  require(direction.allFinite() && direction.norm() > 0.0, "direction of a sine motion must not be zero");
  require(std::isfinite(amplitude) && amplitude >= 0.0, "amplitude of a sine motion must not be negative");
  require(std::isfinite(ramp_duration) && ramp_duration >= 0.0, "ramp duration must not be negative");
  direction_.normalize();
}

Eigen::Vector3d TaperedSineGroundMotion::acceleration(double t) const {
  if (t < 0.0 || t > duration()) return Eigen::Vector3d::Zero();
  const double taper =
      t < ramp_duration_ ? 0.5 * (1.0 - std::cos(std::numbers::pi * t / ramp_duration_)) : 1.0;
  return (taper * amplitude_ * std::sin(phase(t))) * direction_;
}

HarmonicGroundMotion::HarmonicGroundMotion(const Eigen::Vector3d& direction, double amplitude, double frequency,
                                           double ramp_duration)
    : TaperedSineGroundMotion(direction, amplitude, ramp_duration), frequency_(frequency) {
  require(std::isfinite(frequency) && frequency > 0.0, "frequency of a harmonic motion must be positive");
}

double HarmonicGroundMotion::duration() const { return std::numeric_limits<double>::infinity(); }

double HarmonicGroundMotion::phase(double t) const { return 2.0 * std::numbers::pi * frequency_ * t; }

SweepGroundMotion::SweepGroundMotion(const Eigen::Vector3d& direction, double amplitude, double start_frequency,
                                     double end_frequency, double sweep_duration, double ramp_duration)
    : TaperedSineGroundMotion(direction, amplitude, ramp_duration),
      start_frequency_(start_frequency),
      end_frequency_(end_frequency),
      sweep_duration_(sweep_duration) {
  require(std::isfinite(start_frequency) && start_frequency > 0.0 && std::isfinite(end_frequency) &&
              end_frequency > 0.0,
          "frequencies of a sweep must be positive");
  require(std::isfinite(sweep_duration) && sweep_duration > 0.0, "sweep duration must be positive");
}

double SweepGroundMotion::phase(double t) const {
  const double sweep_rate = (end_frequency_ - start_frequency_) / sweep_duration_;  // Hz/s
  return 2.0 * std::numbers::pi * (start_frequency_ * t + 0.5 * sweep_rate * t * t);
}

}  // namespace tankfsi
