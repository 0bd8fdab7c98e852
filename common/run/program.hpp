#pragma once
// run_program: the common life of every tankfsi executable.
//
//   1. parse the command line; start MPI and PETSc with the PETSc options only
//   2. --help / --version
//   3. read and validate the case (bad input: message naming file, line and key,
//      exit status 2, nothing written)
//   4. claim the run folder; write case.resolved.yaml, provenance.json, run.log
//   5. run the program's body, timing its stages
//   6. merge the body's results and the timings into summary.json
// Exit status: 0 success, 1 run-time failure, 2 bad input.
#include <mpi.h>

#include <functional>
#include <nlohmann/json.hpp>

#include "common/cli/command_line.hpp"
#include "common/config/case_config.hpp"
#include "common/log/logger.hpp"
#include "common/log/stage_timers.hpp"
#include "common/run/run_folder.hpp"

namespace tankfsi {

struct ProgramContext {
  const CommandLine& command_line;
  const CaseConfig& config;
  const RunFolder* folder;  ///< null when the program was asked not to write one
  Logger& log;
  StageTimers& timers;
  MPI_Comm comm;
};

/// The program's work; returns its results for summary.json (merged at top level).
using ProgramBody = std::function<nlohmann::json(ProgramContext&)>;
/// Whether this invocation writes a run folder (default: always).
using RunFolderPolicy = std::function<bool(const CommandLine&)>;

int run_program(int argc, char** argv, const ProgramInfo& program, const ProgramBody& body,
                const RunFolderPolicy& writes_run_folder = nullptr);

}  // namespace tankfsi
