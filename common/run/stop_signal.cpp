#include "common/run/stop_signal.hpp"

#include <csignal>

#include "common/io/number_text.hpp"

namespace tankfsi {
namespace {

volatile std::sig_atomic_t received = 0;

extern "C" void note_stop_signal(int signal) {
  received = signal;
  // SA_RESETHAND has put the default action back: a second signal ends the process.
}

}  // namespace

void install_stop_signal_handlers() {
  struct sigaction action{};
  action.sa_handler = note_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND | SA_RESTART;  // system calls in progress go on
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGUSR1, &action, nullptr);
}

int received_stop_signal() { return received; }

int agreed_stop_signal(MPI_Comm comm) {
  int signal = received;
  MPI_Allreduce(MPI_IN_PLACE, &signal, 1, MPI_INT, MPI_MAX, comm);
  return signal;
}

const char* stop_signal_name(int signal) {
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGUSR1) return "SIGUSR1";
  return "a signal";
}

void simulate_stop_signal(int signal) { received = signal; }

StopRequested stopped_after_checkpoint(int signal, double t, const std::filesystem::path& checkpoint) {
  return {std::string("stopped by ") + stop_signal_name(signal) + " at t = " + number_text(t) +
              " s; continue with --restart (checkpoint " + checkpoint.string() + ")",
          checkpoint};
}

}  // namespace tankfsi
