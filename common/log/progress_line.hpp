#pragma once
// ProgressLine: the one-line progress display of a long run on a terminal,
//
//   fem_solver  t = 12.40 / 20.00 s  62.0 %  1843 steps/s  ETA 0:04:07
//
// redrawn in place (carriage return) at most a few times a second, by rank 0
// only, and only when standard error is a terminal: a batch job's log gets
// nothing from it. The rate and the time left come from the wall time since
// the display started. The line is cleared at the end.
#include <chrono>
#include <cstdio>
#include <string>

namespace tankfsi {

class ProgressLine {
 public:
  /// `enabled`: draw at all (rank 0 of a program that runs on a terminal; see
  /// on_terminal()). `stream`: where to draw (standard error by default).
  ProgressLine(std::string program, double end_time, bool enabled, std::FILE* stream = stderr);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// The run has reached simulated time `t` after `steps` steps.
  void update(double t, long long steps);
  /// Removes the line (the next output starts on a clean line).
  void clear();

  /// The text of the line for these figures (what update() draws).
  [[nodiscard]] static std::string format(const std::string& program, double t, double end_time, double steps_per_second,
                                          double seconds_left);
  /// True when `stream` is a terminal.
  [[nodiscard]] static bool on_terminal(std::FILE* stream = stderr);

 private:
  using Clock = std::chrono::steady_clock;
  std::string program_;
  double end_time_;
  bool enabled_;
  std::FILE* stream_;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  double start_time_ = -1.0;
  long long start_steps_ = 0;
  std::size_t drawn_length_ = 0;
};

}  // namespace tankfsi
