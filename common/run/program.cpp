#include "common/run/program.hpp"

#include <chrono>
#include <iostream>
#include <optional>

#include "common/config/case_schema.hpp"
#include "common/parallel/mpi_session.hpp"
#include "common/run/provenance.hpp"
#include "common/run/stop_signal.hpp"

namespace tankfsi {

namespace {

constexpr int exit_success = 0;
constexpr int exit_failure = 1;

// Ends the job from a failure that may have hit only some ranks: the others may
// be waiting in a collective call and would never return, and a partner
// program would wait for data that never comes. MPI_Abort on the world ends
// both programs of a coupled job.
[[noreturn]] void abort_job(int status) {
  MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

int job_size() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int run_work(const CommandLine& cli, const CaseConfig& config, const ProgramInfo& program, const ProgramSetup& setup,
             bool with_folder, MPI_Comm comm, MPI_Comm partner) {
  const CommInfo info = comm_info(comm);
  Logger log(comm, program.name, parse_log_level(config.text("output.log_level")));
  // Set-up errors are input errors met identically on every rank (the same files
  // read the same way): they return normally, nothing written.
  const ProgramWork work = setup(ProgramInputs{cli, config, log, comm, partner});
  std::optional<RestartPoint> restart;
  if (cli.restart) {
    if (!with_folder) throw ConfigError(Origin{"--restart", 0}, "", "this invocation writes no run folder to continue");
    restart = find_restart_point(comm, config.path("output.dir"), program.name, *cli.restart, config);
    if (program.restarts_on_same_ranks_only && restart->ranks != info.size)
      throw ConfigError(Origin{"--restart", 0}, "", restart->path.string() + " was written on " +
                                                        std::to_string(restart->ranks) + " rank(s); " + program.name +
                                                        " continues only on as many, not " + std::to_string(info.size));
  }
  std::optional<RunFolder> folder;
  if (with_folder) {
    try {
      folder = restart ? RunFolder::reopen(comm, config.path("output.dir"), program.name)
                       : RunFolder::claim(comm, config.path("output.dir"), program.name);
    } catch (const std::runtime_error& e) {
      throw config.error_at("output.dir", e.what());
    }
    log.attach_file(folder->path() / "run.log");
    if (info.rank == 0) {
      folder->write_file("case.resolved.yaml", config.resolved_yaml());
    }
    const auto provenance = program_provenance(comm, program.name, cli.arguments, config.file().string());
    if (info.rank == 0)
      folder->merge_json("provenance.json", {{"tankfsi_version", tankfsi_version()},
                                             {"git_commit", tankfsi_git_commit()},
                                             {"programs", {{program.name, provenance}}}});
    log.info(program.name, " ", tankfsi_version(), " (", tankfsi_git_commit(), ") on ", info.size, " rank(s)");
    log.info("case ", config.file().string(), config.text("title").empty() ? "" : ": " + config.text("title"));
    log.info("run folder ", folder->path().string());
    if (restart)
      log.info("restart from ", restart->path.string(), " (checkpoint ", restart->number, ", t = ", restart->time,
               " s, written on ", restart->ranks, " rank(s))");
  }

  StageTimers timers;
  ProgramContext context{cli, config, folder ? &*folder : nullptr, log, timers, comm, partner, restart};
  install_stop_signal_handlers();
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json results;
  try {
    results = work(context);
  } catch (const StopRequested& e) {
    log.info(e.what());
    if (folder && info.rank == 0)
      folder->merge_json("summary.json", {{"programs", {{program.name, {{"status", "stopped"}, {"checkpoint", e.checkpoint().string()}}}}}});
    return exit_status_stopped;
  } catch (const ConfigError& e) {
    log.error(e.what());
    if (job_size() > 1) abort_job(exit_status_bad_input);
    return exit_status_bad_input;
  } catch (const std::exception& e) {
    log.error(e.what());
    if (job_size() > 1) abort_job(exit_failure);
    return exit_failure;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (folder && info.rank == 0) {
    nlohmann::json part = results.is_object() ? results : nlohmann::json::object();
    part["programs"][program.name] = {{"status", "finished"}, {"wall_time_s", wall}, {"stages", timers.to_json()}};
    folder->merge_json("summary.json", part);
  }
  // A run without a folder only answers a question (check a case): its output
  // is the answer, with no log lines mixed in.
  if (folder) {
    if (!timers.to_json().empty()) log.info("stage timings (rank 0):\n", timers.table());
    log.info(program.name, " finished in ", wall, " s");
  }
  return exit_success;
}

}  // namespace

int run_program(int argc, char** argv, const ProgramInfo& program, const ProgramSetup& setup,
                const RunFolderPolicy& writes_run_folder) {
  std::optional<CommandLine> cli;
  std::string command_line_error;
  try {
    cli = parse_command_line(argc, argv, program);
  } catch (const ConfigError& e) {
    command_line_error = e.what();
  }
  MpiSession session(cli ? cli->petsc_arguments : std::vector<std::string>{argc > 0 ? argv[0] : program.name},
                     program.role);
  const bool printer = session.rank() == 0;

  // In a coupled job the partner would wait for this program: bad input ends both.
  const auto bad_input = [&session] {
    if (session.partner() != MPI_COMM_NULL) abort_job(exit_status_bad_input);
    return exit_status_bad_input;
  };
  if (!command_line_error.empty()) {
    if (printer) std::cerr << program.name << ": error: " << command_line_error << "\n";
    return bad_input();
  }
  if (cli->help) {
    if (printer) std::cout << help_text(program, case_schema());
    return exit_success;
  }
  if (cli->version) {
    if (printer) std::cout << program.name << " " << tankfsi_version() << " (" << tankfsi_git_commit() << ")\n";
    return exit_success;
  }

  std::vector<Override> overrides = cli->overrides;
  if (cli->output_dir)
    overrides.push_back(Override{"output.dir", cli->output_dir->string(), "--output " + cli->output_dir->string()});
  try {
    // Every rank reads and validates: the same file gives the same verdict everywhere.
    const CaseConfig config = CaseConfig::load(cli->case_file, overrides, case_schema());
    const bool with_folder = !writes_run_folder || writes_run_folder(*cli);
    return run_work(*cli, config, program, setup, with_folder, session.world(), session.partner());
  } catch (const ConfigError& e) {
    if (printer) std::cerr << program.name << ": error: " << e.what() << std::endl;
    return bad_input();
  } catch (const std::exception& e) {
    std::cerr << program.name << ": error (rank " << session.rank() << "): " << e.what() << "\n";
    if (session.job_size() > 1) abort_job(exit_failure);
    return exit_failure;
  }
}

}  // namespace tankfsi
