#pragma once
// Logger: rank-aware messages for a parallel program.
//
// info, warning and debug messages are printed by rank 0 of the program's
// communicator only (they say the same thing on every rank); errors are printed
// by whichever rank meets them, tagged with its rank, because they may differ.
// With a log file, the same lines go to run.log in the run folder, opened in
// append mode so that both partner programs of a coupled job share it.
#include <mpi.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

namespace tankfsi {

enum class LogLevel { error = 0, warning = 1, info = 2, debug = 3 };

/// Parses "error|warning|info|debug" (output.log_level).
LogLevel parse_log_level(const std::string& text);

class Logger {
 public:
  Logger(MPI_Comm comm, std::string program, LogLevel level);
  ~Logger();
  Logger(const Logger&) = delete;
  Logger& operator=(const Logger&) = delete;

  /// From now on, lines also go to `path` (appended).
  void attach_file(const std::filesystem::path& path);
  void set_level(LogLevel level) { level_ = level; }

  template <class... Parts>
  void error(const Parts&... parts) { write(LogLevel::error, concat(parts...)); }
  template <class... Parts>
  void warning(const Parts&... parts) { write(LogLevel::warning, concat(parts...)); }
  template <class... Parts>
  void info(const Parts&... parts) { write(LogLevel::info, concat(parts...)); }
  template <class... Parts>
  void debug(const Parts&... parts) { write(LogLevel::debug, concat(parts...)); }

  [[nodiscard]] int rank() const { return rank_; }

 private:
  template <class... Parts>
  static std::string concat(const Parts&... parts) {
    std::ostringstream out;
    (out << ... << parts);
    return out.str();
  }
  void write(LogLevel level, const std::string& message);

  std::string program_;
  LogLevel level_;
  int rank_ = 0;
  int size_ = 1;
  std::FILE* file_ = nullptr;
};

}  // namespace tankfsi
