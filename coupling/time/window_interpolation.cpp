#include "coupling/time/window_interpolation.hpp"

#include <stdexcept>
#include <string>

namespace tankfsi::coupling {

namespace {

void require_size(std::size_t got, std::size_t expected, const char* what) {
  if (got != expected)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(got) + " values, expected " +
                                std::to_string(expected));
}

void lerp(const std::vector<double>& a, const std::vector<double>& b, double fraction, std::span<double> out) {
  require_size(out.size(), a.size(), "interpolated values");
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] + (b[i] - a[i]) * fraction;
}

std::vector<double> lerp(const std::vector<double>& a, const std::vector<double>& b, double fraction) {
  std::vector<double> v(a.size());
  lerp(a, b, fraction, v);
  return v;
}

}  // namespace

void WindowAverage::add(std::span<const double> values, double dt) {
  require_size(values.size(), impulse_.size(), "window average");
  for (std::size_t i = 0; i < values.size(); ++i) impulse_[i] += values[i] * dt;
  duration_ += dt;
}

std::vector<double> WindowAverage::average(double window_length) const {
  std::vector<double> a(impulse_.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = impulse_[i] / window_length;
  return a;
}

void WindowAverage::reset() {
  std::fill(impulse_.begin(), impulse_.end(), 0.0);
  duration_ = 0.0;
}

void LoadRamp::aim(std::span<const double> average, double chi) {
  require_size(average.size(), start_.size(), "load ramp");
  for (std::size_t i = 0; i < start_.size(); ++i) end_[i] = start_[i] + chi * (average[i] - start_[i]);
}

void LoadRamp::hold(std::span<const double> average) {
  require_size(average.size(), start_.size(), "load ramp");
  start_.assign(average.begin(), average.end());
  end_ = start_;
}

std::vector<double> LoadRamp::at(double fraction) const { return lerp(start_, end_, fraction); }
void LoadRamp::at(double fraction, std::span<double> out) const { lerp(start_, end_, fraction, out); }

std::vector<double> LoadRamp::mean() const { return lerp(start_, end_, 0.5); }

std::vector<double> DisplacementPath::at(double fraction) const { return lerp(start_, target_, fraction); }
void DisplacementPath::at(double fraction, std::span<double> out) const { lerp(start_, target_, fraction, out); }

std::vector<double> DisplacementPath::velocity(double window_length) const {
  std::vector<double> v(start_.size());
  velocity(window_length, v);
  return v;
}

void DisplacementPath::velocity(double window_length, std::span<double> out) const {
  require_size(out.size(), start_.size(), "wall velocity");
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = (target_[i] - start_[i]) / window_length;
}

}  // namespace tankfsi::coupling
