#pragma once
// CheckpointSeries: the checkpoints one program writes into its run folder,
//
//   RUN/checkpoints/<program>_<k>.h5     k = 1, 2, ... (six digits)
//
// each a complete state from which the program continues (`--restart`). The
// two programs of a coupled job write theirs at the same coupling window
// under the same number k. A checkpoint is written as <name>.h5.partial and
// renamed when complete, so a run killed while writing keeps the ones before;
// after each rename all but the program's last two are removed (two, so that
// a partner one checkpoint behind still finds a common one).
//
// Every checkpoint carries, as attributes of its root group: program, number,
// time_s, ranks, the resolved case (case_yaml) and the version that wrote it.
#include <mpi.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/config/case_config.hpp"
#include "common/io/hdf5_file.hpp"

namespace tankfsi {

class CheckpointSeries {
 public:
  /// `run_folder`: the run's folder; `program`: the writing program's name.
  /// `first`: the number of the first checkpoint to write (1, or the one
  /// after the checkpoint a restart continues from).
  CheckpointSeries(MPI_Comm comm, std::filesystem::path run_folder, std::string program, int first = 1);

  [[nodiscard]] std::filesystem::path path(int number) const;
  /// Collective: opens the next checkpoint (as .partial) with its root
  /// attributes written; the caller adds its state, then calls commit().
  [[nodiscard]] std::unique_ptr<Hdf5File> begin(double time, const CaseConfig& config);
  /// Collective: closes `file`, renames it into place and removes the
  /// program's checkpoints older than the last two. Returns its path.
  std::filesystem::path commit(std::unique_ptr<Hdf5File> file);
  [[nodiscard]] int written() const { return next_ - first_; }

 private:
  MPI_Comm comm_;
  std::filesystem::path folder_;
  std::string program_;
  int first_;
  int next_;
};

/// The time of the next periodic checkpoint or output after `t`: the next
/// multiple of `interval` (output.checkpoint_interval, field_interval, ...),
/// infinity for interval 0 (none).
[[nodiscard]] double next_output_time(double t, double interval);

/// Whether a program writes a checkpoint after its step, and whether it stops
/// there (the signal's number; 0: goes on).
struct CheckpointDecision {
  bool due = false;
  int stop_signal = 0;
};

/// Collective, a program running alone, after a step that ended at `t`: a
/// checkpoint is due at the first step end at or after `next_time` (then
/// moved on by `interval`) and on a stop signal any rank received.
[[nodiscard]] CheckpointDecision checkpoint_after_step(MPI_Comm comm, double t, double interval, double& next_time);

/// A coupled program, after a step: where the coupling agreed a restart
/// point (FluidCoupling, StructureCoupling: restart_point_due(), stop_signal()).
template <class Coupling>
[[nodiscard]] CheckpointDecision checkpoint_after_window(Coupling& coupling) {
  const bool due = coupling.restart_point_due();
  return {due, due ? coupling.stop_signal() : 0};
}

/// After a failed step, with the program at its last good state: writes it
/// as a checkpoint with `write` and returns " and checkpoint PATH" for the
/// error message, or " (no checkpoint: why)" if writing failed too.
[[nodiscard]] std::string last_good_checkpoint(const std::function<std::filesystem::path()>& write);

/// A checkpoint to restart from, opened for reading on every rank of `comm`.
struct RestartPoint {
  std::filesystem::path path;
  int number = 0;
  double time = 0.0;
  int ranks = 0;  ///< ranks of the program that wrote it
};

/// Collective: the checkpoint `spec` names for `program` in `run_folder`:
/// "latest" (or empty) — the highest number that every program that ran in
/// the folder (its .claims) has a checkpoint of; a number; or a path to one
/// of the program's checkpoints. Checks that it was written for a case that
/// differs from `config` in nothing but restart_case_differences() leaves out. Throws
/// ConfigError (origin "--restart") naming what is missing or different.
RestartPoint find_restart_point(MPI_Comm comm, const std::filesystem::path& run_folder, const std::string& program,
                                const std::string& spec, const CaseConfig& config);

/// The keys (sections, or top-level keys) in which two resolved cases
/// differ, leaving out title, output and end_time, and what does not change
/// the state: fluid.ppe.solver_options, fluid.time_step.breach_courant,
/// structure.solver_options, coupling.timeout.
std::vector<std::string> restart_case_differences(const std::string& written_yaml, const std::string& current_yaml);

}  // namespace tankfsi
