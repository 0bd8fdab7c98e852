#pragma once
// Time treatment of interface data within one coupling window [t_n, t_n + dt_c]
// (METHOD.md §4, eqs 16-18). The window length may be shorter than dt_c for
// the last window of a run.
#include <span>
#include <vector>

namespace tankfsi::coupling {

/// Eq 16: the window-average force F̄ = (1/dt_c) sum_k F^k dt_s of the fluid's
/// sub-steps, each force held over its own step (sub-steps of any length).
class WindowAverage {
 public:
  explicit WindowAverage(std::size_t size = 0) : impulse_(size, 0.0) {}
  void add(std::span<const double> values, double dt);
  /// The impulse so far divided by `window_length`.
  [[nodiscard]] std::vector<double> average(double window_length) const;
  [[nodiscard]] double duration() const { return duration_; }
  void reset();

 private:
  std::vector<double> impulse_;
  double duration_ = 0.0;
};

/// Eq 17: the structure's load over a window, linear from the load it applies
/// at the window start, L_start, to L_end = L_start + chi (F̄ - L_start), where
/// F̄ is the fluid's window average it is given. This is eq 17's recursion
/// F^k = F^{k-1} + (chi/dt_c)(F̄^{n+1} - F̄^n) dt_f summed over the window, with
/// F̄^n read as the load applied at the window start (with chi = 1 that is the
/// previous window's average, as in the paper). chi = 1: the load reaches F̄
/// at the window end (smooth, half a window late); chi = 2: the window's
/// impulse dt_c (L_start + L_end)/2 equals dt_c F̄ exactly (the load zig-zags).
class LoadRamp {
 public:
  explicit LoadRamp(std::vector<double> initial_load = {}) : start_(initial_load), end_(std::move(initial_load)) {}
  /// Sets the end of the current window from the window average `average`.
  void aim(std::span<const double> average, double chi);
  /// The alternative to eq 17: the load is `average` over the whole window
  /// (start and end alike), so the window's impulse is exact without the
  /// ramp's zig-zag (chi = 2) or lag (chi = 1).
  void hold(std::span<const double> average);
  /// The load at `fraction` (0 = window start, 1 = end) of the window.
  [[nodiscard]] std::vector<double> at(double fraction) const;
  void at(double fraction, std::span<double> out) const;
  /// The window's impulse per value divided by its length: (L_start + L_end)/2.
  [[nodiscard]] std::vector<double> mean() const;
  /// The next window starts where this one ended.
  void next_window() { start_ = end_; }
  [[nodiscard]] const std::vector<double>& start() const { return start_; }
  [[nodiscard]] const std::vector<double>& end() const { return end_; }

 private:
  std::vector<double> start_;
  std::vector<double> end_;
};

/// Eq 18: the wall moves with constant velocity over the window, from where
/// it is at the window start to the target displacement it was given.
class DisplacementPath {
 public:
  explicit DisplacementPath(std::vector<double> initial = {}) : start_(initial), target_(std::move(initial)) {}
  void aim(std::vector<double> target) { target_ = std::move(target); }
  [[nodiscard]] std::vector<double> at(double fraction) const;
  void at(double fraction, std::span<double> out) const;
  /// (target - start) / window_length: the wall velocity of the window.
  [[nodiscard]] std::vector<double> velocity(double window_length) const;
  void velocity(double window_length, std::span<double> out) const;
  void next_window() { start_ = target_; }
  [[nodiscard]] const std::vector<double>& start() const { return start_; }
  [[nodiscard]] const std::vector<double>& target() const { return target_; }

 private:
  std::vector<double> start_;
  std::vector<double> target_;
};

}  // namespace tankfsi::coupling
