#include "common/log/logger.hpp"

#include <unistd.h>

#include <stdexcept>

#include "common/run/provenance.hpp"

namespace tankfsi {

LogLevel parse_log_level(const std::string& text) {
  if (text == "error") return LogLevel::error;
  if (text == "warning") return LogLevel::warning;
  if (text == "info") return LogLevel::info;
  if (text == "debug") return LogLevel::debug;
  throw std::invalid_argument("unknown log level '" + text + "'");
}

Logger::Logger(MPI_Comm comm, std::string program, LogLevel level) : program_(std::move(program)), level_(level) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
}

Logger::~Logger() {
  if (file_) std::fclose(file_);
}

void Logger::attach_file(const std::filesystem::path& path) {
  if (file_) std::fclose(file_);
  file_ = std::fopen(path.c_str(), "a");
  if (!file_) throw std::runtime_error("cannot open log file '" + path.string() + "'");
}

void Logger::write(LogLevel level, const std::string& message) {
  if (level > level_) return;
  if (level != LogLevel::error && rank_ != 0) return;
  static constexpr const char* names[] = {"error", "warning", "info", "debug"};
  const std::string tag = size_ > 1 && level == LogLevel::error ? " rank " + std::to_string(rank_) : "";
  const std::string console = level == LogLevel::info ? message + "\n"
                                                      : std::string(names[static_cast<int>(level)]) + tag + ": " + message + "\n";
  std::FILE* stream = level <= LogLevel::warning ? stderr : stdout;
  std::fputs(console.c_str(), stream);
  std::fflush(stream);
  if (file_) {
    // One write per line: appends from several processes do not interleave within a line.
    const std::string line = utc_timestamp() + " [" + program_ + tag + "] " + names[static_cast<int>(level)] + ": " + message + "\n";
    std::fputs(line.c_str(), file_);
    std::fflush(file_);
  }
}

}  // namespace tankfsi
