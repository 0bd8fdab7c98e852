#pragma once
// CommandLine: what a tankfsi program was asked to do.
//
//   PROGRAM [options] CASE.yaml [PETSc options]
//     --set KEY=VALUE   override a case key (validated like the file; repeatable)
//     --output DIR      run folder (overrides output.dir)
//     --restart [latest|N|FILE]  continue the run in the run folder from a checkpoint
//     --help            usage and every case key with unit and default
//     --version
// Single-dash options (-log_view, -ppe_ksp_type cg, ...) and their values go to
// PETSc untouched. The case file is the one argument ending in .yaml or .yml.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/config/case_config.hpp"

namespace tankfsi {

/// The banner every program prints with --help: what it solves, sample runs.
struct ProgramInfo {
  std::string name;         ///< executable name, also its role in the run folder
  std::string purpose;      ///< one paragraph
  std::vector<std::string> examples;  ///< copy-pasteable command lines
  std::vector<std::string> flags;     ///< extra flags the program accepts: "--prepare  Writes ..."
  std::string role;                   ///< role in a coupled job ("fluid", "structure"); empty: never couples
  bool restarts_on_same_ranks_only = false;  ///< --restart refuses a checkpoint of another rank count
};

struct CommandLine {
  std::filesystem::path case_file;
  std::vector<Override> overrides;
  std::optional<std::filesystem::path> output_dir;
  /// --restart: "latest", a checkpoint number or a checkpoint file.
  std::optional<std::string> restart;
  bool help = false;
  bool version = false;
  std::vector<std::string> program_flags;    ///< flags from ProgramInfo::flags that were given
  std::vector<std::string> petsc_arguments;  ///< argv[0] and everything meant for PETSc
  std::vector<std::string> arguments;        ///< the whole command line, for provenance
  [[nodiscard]] bool has_flag(const std::string& flag) const;
};

/// Parses argv; throws ConfigError (origin "command line") on a malformed line.
CommandLine parse_command_line(int argc, const char* const* argv, const ProgramInfo& program);

/// Usage, banner and the full key listing generated from the schema.
std::string help_text(const ProgramInfo& program, const Schema& schema);

}  // namespace tankfsi
