#pragma once
// WindowReportFile: probes/coupling.csv, one row per accepted coupling window
// (time_s is the window's end): its coupling iterations, whether it
// converged, the last relative residuals, and the impulse the fluid gave
// against the impulse the structure applied (the structure side knows both).
#include <filesystem>
#include <memory>
#include <optional>

#include "common/io/probe_file.hpp"
#include "coupling/participant.hpp"

namespace tankfsi::coupling {

class WindowReportFile {
 public:
  /// `resume_time`: a restart's time; the file keeps its rows up to it.
  WindowReportFile(const std::filesystem::path& path, double flush_interval,
                   std::optional<double> resume_time = std::nullopt);
  void append(const WindowReport& report, const CouplingTimings& timings);
  void flush() { file_->flush(); }

 private:
  std::unique_ptr<ProbeFile> file_;
};

}  // namespace tankfsi::coupling
