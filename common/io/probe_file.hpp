#pragma once
// ProbeFile: one probe's time series as CSV, probes/<name>.csv.
//
//   time_s,wave_height_m,pressure_Pa
//   0,0.0012,6713.2
//
// Column names carry their unit (DESIGN.md conventions). Rows are flushed to disk
// whenever simulated time has advanced by flush_interval since the last flush,
// so a killed run keeps its history up to the last output interval.
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace tankfsi {

class ProbeFile {
 public:
  /// Creates (truncates) the file and writes the header: time_s, then `columns`.
  ProbeFile(const std::filesystem::path& path, std::vector<std::string> columns, double flush_interval);

  /// Continues the file of a run restarted at `resume_time`: keeps its rows up
  /// to that time (those after it are the stopped run's, computed again) and
  /// appends after them. The file must exist with the same header; throws
  /// std::runtime_error otherwise.
  ProbeFile(const std::filesystem::path& path, std::vector<std::string> columns, double flush_interval,
            double resume_time);

  /// One row; `values` must match the columns. Times must not decrease.
  void append(double time, std::span<const double> values);
  void flush();

  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  double flush_interval_;
  double last_flush_time_;
  double last_time_;
  std::ofstream out_;

  void check_columns() const;
  [[nodiscard]] std::string header() const;
};

/// A new probe file, or with `resume_time` the continued one of a restart.
std::unique_ptr<ProbeFile> open_probe_file(const std::filesystem::path& path, std::vector<std::string> columns,
                                           double flush_interval, std::optional<double> resume_time);

}  // namespace tankfsi
