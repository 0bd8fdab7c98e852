#pragma once
// Stop signals: what a batch scheduler sends before a job's time limit
// (SIGTERM, or SIGUSR1 with Slurm's --signal). The handler only sets a flag;
// the run looks at it between steps (alone) or at the end of a coupling
// window (with a partner), writes a checkpoint there and stops with
// exit_status_stopped. A second signal of the same kind is not caught: it
// ends the process at once, as without a handler.
#include <mpi.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace tankfsi {

/// Exit status of a run stopped by a signal after writing its checkpoint.
inline constexpr int exit_status_stopped = 3;

/// Installs the handlers for SIGTERM and SIGUSR1 (once per process).
void install_stop_signal_handlers();
/// The signal this process received (0: none).
[[nodiscard]] int received_stop_signal();
/// Collective over `comm`: the signal any of its ranks received (0: none).
[[nodiscard]] int agreed_stop_signal(MPI_Comm comm);
/// "SIGTERM", "SIGUSR1", or the number.
[[nodiscard]] const char* stop_signal_name(int signal);
/// Thrown by a program's work, on every rank, after it wrote its checkpoint
/// on a stop signal: run_program logs it and exits with exit_status_stopped.
/// (Not a std::runtime_error: the handlers of failed steps must let it pass.)
class StopRequested : public std::exception {
 public:
  StopRequested(std::string message, std::filesystem::path checkpoint)
      : message_(std::move(message)), checkpoint_(std::move(checkpoint)) {}
  [[nodiscard]] const char* what() const noexcept override { return message_.c_str(); }
  [[nodiscard]] const std::filesystem::path& checkpoint() const { return checkpoint_; }

 private:
  std::string message_;
  std::filesystem::path checkpoint_;
};

/// The StopRequested of a program that wrote `checkpoint` at time `t` on `signal`.
[[nodiscard]] StopRequested stopped_after_checkpoint(int signal, double t, const std::filesystem::path& checkpoint);

/// For tests: behaves as if `signal` had arrived (0 clears).
void simulate_stop_signal(int signal);

}  // namespace tankfsi
