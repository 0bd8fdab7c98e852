#include "common/cli/command_line.hpp"

#include <algorithm>
#include <sstream>

namespace tankfsi {

namespace {

const Origin command_line_origin{"command line", 0};

bool is_case_file(const std::string& argument) {
  return argument.ends_with(".yaml") || argument.ends_with(".yml");
}

std::string flag_name(const std::string& flag_line) { return flag_line.substr(0, flag_line.find(' ')); }

Override parse_override(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw ConfigError(command_line_origin, "", "--set needs KEY=VALUE, got '" + text + "'");
  return Override{text.substr(0, equals), text.substr(equals + 1), ""};
}

}  // namespace

bool CommandLine::has_flag(const std::string& flag) const {
  return std::find(program_flags.begin(), program_flags.end(), flag) != program_flags.end();
}

CommandLine parse_command_line(int argc, const char* const* argv, const ProgramInfo& program) {
  CommandLine cli;
  cli.arguments.assign(argv, argv + argc);
  cli.petsc_arguments.push_back(argc > 0 ? argv[0] : program.name);
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    // Options with a value accept both "--key value" and "--key=value".
    auto value_of = [&](const std::string& option) -> std::optional<std::string> {
      if (argument == option) {
        if (i + 1 >= argc) throw ConfigError(command_line_origin, "", option + " needs a value");
        return std::string(argv[++i]);
      }
      if (argument.starts_with(option + "=")) return argument.substr(option.size() + 1);
      return std::nullopt;
    };
    if (argument == "--help" || argument == "-h") {
      cli.help = true;
    } else if (argument == "--version") {
      cli.version = true;
    } else if (auto set = value_of("--set")) {
      cli.overrides.push_back(parse_override(*set));
    } else if (auto output = value_of("--output")) {
      if (output->empty()) throw ConfigError(command_line_origin, "", "--output needs a folder");
      cli.output_dir = *output;
    } else if (argument == "--restart") {
      // The value is optional: a following case file or option is not one.
      const bool valued = i + 1 < argc && argv[i + 1][0] != '-' && !is_case_file(argv[i + 1]);
      cli.restart = valued ? std::string(argv[++i]) : std::string("latest");
    } else if (auto restart = value_of("--restart")) {
      if (restart->empty()) throw ConfigError(command_line_origin, "", "--restart= needs latest, a number or a file");
      cli.restart = *restart;
    } else if (argument.starts_with("--")) {
      const auto known = std::find_if(program.flags.begin(), program.flags.end(),
                                      [&](const std::string& f) { return flag_name(f) == argument; });
      if (known == program.flags.end())
        throw ConfigError(command_line_origin, "", "unknown option " + argument + " (see --help)");
      cli.program_flags.push_back(argument);
    } else if (argument.starts_with("-") && argument.size() > 1) {
      // A PETSc option; a following word that is not a case file is its value.
      cli.petsc_arguments.push_back(argument);
      if (i + 1 < argc && argv[i + 1][0] != '-' && !is_case_file(argv[i + 1])) cli.petsc_arguments.emplace_back(argv[++i]);
    } else if (is_case_file(argument)) {
      if (!cli.case_file.empty())
        throw ConfigError(command_line_origin, "", "two case files given: " + cli.case_file.string() + " and " + argument);
      cli.case_file = argument;
    } else {
      throw ConfigError(command_line_origin, "",
                        "unexpected argument '" + argument + "' (the case file must end in .yaml or .yml)");
    }
  }
  if (cli.case_file.empty() && !cli.help && !cli.version)
    throw ConfigError(command_line_origin, "", "no case file given (usage: " + program.name +
                                                   " [options] CASE.yaml; see --help)");
  return cli;
}

std::string help_text(const ProgramInfo& program, const Schema& schema) {
  std::ostringstream out;
  out << program.name << ": " << program.purpose << "\n\n"
      << "Usage: " << program.name << " [options] CASE.yaml [PETSc options]\n\n"
      << "Options:\n"
      << "  --set KEY=VALUE   override a case key, e.g. --set fluid.spacing=0.02 (repeatable)\n"
      << "  --output DIR      run folder, overrides output.dir\n"
      << "  --restart [latest|N|FILE]\n"
      << "                    continue the run in the run folder from its latest checkpoint (default),\n"
      << "                    checkpoint N, or a checkpoint file; the case may change only title,\n"
      << "                    output and end_time\n";
  for (const auto& flag : program.flags) out << "  " << flag << "\n";
  out << "  --help            this text\n"
      << "  --version         version and git commit\n"
      << "  -OPTION [VALUE]   passed to PETSc, e.g. -log_view, -ppe_ksp_type cg\n";
  if (!program.examples.empty()) {
    out << "\nExamples:\n";
    for (const auto& e : program.examples) out << "  " << e << "\n";
  }
  out << "\nExit status: 0 success, 1 run-time failure, 2 bad input (case file, options, files).\n"
      << "\nCase file keys (YAML; SI units; unknown keys are errors):\n"
      << schema_help_text(schema);
  return out.str();
}

}  // namespace tankfsi
