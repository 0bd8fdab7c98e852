#pragma once
// run_program: the common life of every tankfsi executable.
//
//   1. parse the command line; start MPI and PETSc with the PETSc options only
//   2. --help / --version
//   3. read and validate the case, then run the program's set-up, which reads
//      and checks every other input (bad input: a message naming file, line and
//      key, exit status 2, nothing written)
//   4. claim the run folder; write case.resolved.yaml, provenance.json, run.log
//   5. run the program's work, timing its stages
//   6. merge the work's results and the timings into summary.json
//   With --restart the checkpoint is found and checked in 3 (bad input if it
//   is missing or was written for another case), and 4 reopens the folder.
// Exit status: 0 success, 1 run-time failure, 2 bad input, 3 stopped by
// SIGTERM or SIGUSR1 after writing a checkpoint (common/run/stop_signal.hpp).
#include <mpi.h>

#include <functional>
#include <optional>
#include <nlohmann/json.hpp>

#include "common/cli/command_line.hpp"
#include "common/config/case_config.hpp"
#include "common/log/logger.hpp"
#include "common/log/stage_timers.hpp"
#include "common/run/checkpoint_series.hpp"
#include "common/run/run_folder.hpp"

namespace tankfsi {

/// What a program's set-up sees: the validated case, before any file is written.
struct ProgramInputs {
  const CommandLine& command_line;
  const CaseConfig& config;
  Logger& log;
  MPI_Comm comm;
  MPI_Comm partner;  ///< inter-communicator to the partner program, MPI_COMM_NULL alone
};

/// What a program's work sees: the inputs, the run folder and the stage timers.
struct ProgramContext {
  const CommandLine& command_line;
  const CaseConfig& config;
  const RunFolder* folder;  ///< null when the program was asked not to write one
  Logger& log;
  StageTimers& timers;
  MPI_Comm comm;     ///< this program's ranks
  MPI_Comm partner;  ///< inter-communicator to the partner program, MPI_COMM_NULL alone
  /// --restart: the checkpoint to continue from (the folder is the earlier run's).
  std::optional<RestartPoint> restart;
};

/// The program's work once its run folder exists; returns its results for
/// summary.json (merged at the top level).
using ProgramWork = std::function<nlohmann::json(ProgramContext&)>;
/// Reads and checks every input the work needs (meshes, records, ground
/// motions), raising bad input as ConfigError before anything is written, and
/// returns the work.
using ProgramSetup = std::function<ProgramWork(const ProgramInputs&)>;
/// Whether this invocation writes a run folder (default: always).
using RunFolderPolicy = std::function<bool(const CommandLine&)>;

int run_program(int argc, char** argv, const ProgramInfo& program, const ProgramSetup& setup,
                const RunFolderPolicy& writes_run_folder = nullptr);

}  // namespace tankfsi
