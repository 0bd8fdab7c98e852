#include "common/log/progress_line.hpp"

#include <unistd.h>

#include <cmath>

namespace tankfsi {

namespace {

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--:--";
  const auto s = static_cast<long long>(std::llround(seconds));
  char text[32];
  std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", s / 3600, (s / 60) % 60, s % 60);
  return text;
}

}  // namespace

ProgressLine::ProgressLine(std::string program, double end_time, bool enabled, std::FILE* stream)
    : program_(std::move(program)), end_time_(end_time), enabled_(enabled), stream_(stream), start_(Clock::now()),
      last_draw_(start_) {}

ProgressLine::~ProgressLine() { clear(); }

bool ProgressLine::on_terminal(std::FILE* stream) { return isatty(fileno(stream)) == 1; }

std::string ProgressLine::format(const std::string& program, double t, double end_time, double steps_per_second,
                                 double seconds_left) {
  char text[256];
  std::snprintf(text, sizeof text, "%s  t = %.2f / %.2f s  %5.1f %%  %.0f steps/s  ETA %s", program.c_str(), t,
                end_time, end_time > 0 ? 100.0 * t / end_time : 100.0, steps_per_second, clock_text(seconds_left).c_str());
  return text;
}

void ProgressLine::update(double t, long long steps) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (start_time_ < 0) {  // the rate counts from the first update on
    start_time_ = t;
    start_steps_ = steps;
    start_ = now;
    return;
  }
  if (now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double rate = wall > 0 ? static_cast<double>(steps - start_steps_) / wall : 0.0;
  const double simulated_rate = wall > 0 ? (t - start_time_) / wall : 0.0;
  const double left = simulated_rate > 0 ? (end_time_ - t) / simulated_rate : -1.0;
  const std::string line = format(program_, t, end_time_, rate, left);
  std::fprintf(stream_, "\r%s%*s", line.c_str(),
               static_cast<int>(drawn_length_ > line.size() ? drawn_length_ - line.size() : 0), "");
  std::fflush(stream_);
  drawn_length_ = line.size();
}

void ProgressLine::clear() {
  if (!enabled_ || drawn_length_ == 0) return;
  std::fprintf(stream_, "\r%*s\r", static_cast<int>(drawn_length_), "");
  std::fflush(stream_);
  drawn_length_ = 0;
}

}  // namespace tankfsi
