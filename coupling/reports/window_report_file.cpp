#include "coupling/reports/window_report_file.hpp"

namespace tankfsi::coupling {

WindowReportFile::WindowReportFile(const std::filesystem::path& path, double flush_interval,
                                   std::optional<double> resume_time)
    : file_(open_probe_file(path,
                            {"window", "iterations", "converged", "displacement_residual", "force_residual",
                             "impulse_given_x_Ns", "impulse_given_y_Ns", "impulse_given_z_Ns", "impulse_applied_x_Ns",
                             "impulse_applied_y_Ns", "impulse_applied_z_Ns", "coupling_wait_s", "coupling_work_s"},
                            flush_interval, resume_time)) {}

void WindowReportFile::append(const WindowReport& r, const CouplingTimings& timings) {
  const double row[] = {static_cast<double>(r.window),
                        static_cast<double>(r.iterations),
                        r.converged ? 1.0 : 0.0,
                        r.displacement_residual,
                        r.force_residual,
                        r.impulse_given[0],
                        r.impulse_given[1],
                        r.impulse_given[2],
                        r.impulse_applied[0],
                        r.impulse_applied[1],
                        r.impulse_applied[2],
                        timings.wait,
                        timings.work};
  file_->append(r.end_time, row);
}

}  // namespace tankfsi::coupling
