// CommandLine: our options are taken out, PETSc's are passed on untouched.
#include <catch2/catch.hpp>

#include "common/cli/command_line.hpp"
#include "common/config/case_schema.hpp"

using namespace tankfsi;

namespace {
const ProgramInfo program{"prog", "does things", {}, {"--prepare  writes"}, ""};

CommandLine parse(std::vector<const char*> arguments) {
  arguments.insert(arguments.begin(), "prog");
  return parse_command_line(static_cast<int>(arguments.size()), arguments.data(), program);
}
}  // namespace

TEST_CASE("case file, overrides, output folder and PETSc options are told apart", "[cli]") {
  const auto cli = parse({"-log_view", "case.yaml", "--set", "fluid.spacing=0.02", "-ppe_ksp_type", "cg",
                          "--set=output.log_level=debug", "--output=runs/a", "--prepare", "-ppe_ksp_rtol", "1e-10"});
  CHECK(cli.case_file == "case.yaml");
  REQUIRE(cli.overrides.size() == 2);
  CHECK(cli.overrides[0].key == "fluid.spacing");
  CHECK(cli.overrides[0].value == "0.02");
  CHECK(cli.overrides[1].key == "output.log_level");
  CHECK(cli.overrides[1].value == "debug");
  CHECK(cli.output_dir == "runs/a");
  CHECK(cli.has_flag("--prepare"));
  CHECK(cli.petsc_arguments ==
        std::vector<std::string>{"prog", "-log_view", "-ppe_ksp_type", "cg", "-ppe_ksp_rtol", "1e-10"});
}

TEST_CASE("a value with '=' inside keeps it", "[cli]") {
  const auto cli = parse({"c.yml", "--set", "title=a=b"});
  CHECK(cli.overrides.at(0).value == "a=b");
}

TEST_CASE("help needs no case file and lists every key", "[cli]") {
  CHECK(parse({"--help"}).help);
  const auto text = help_text(program, case_schema());
  for (const auto& key : case_schema().keys) CHECK(text.find(key.name) != std::string::npos);
  CHECK(text.find("--prepare") != std::string::npos);
}

TEST_CASE("malformed command lines are errors", "[cli]") {
  CHECK_THROWS_WITH(parse({}), "command line: no case file given (usage: prog [options] CASE.yaml; see --help)");
  CHECK_THROWS_WITH(parse({"c.yaml", "--output"}), "command line: --output needs a value");
  CHECK_THROWS_WITH(parse({"c.yaml", "--set", "=3"}), "command line: --set needs KEY=VALUE, got '=3'");
}
