// tankfsi_case: checks a case file and prepares its run folder.
//
// What it does
//   Validates CASE.yaml against the schema (every key, unit, range and file),
//   applies --set overrides and prints the resolved case. With --prepare it also
//   claims the run folder, writes case.resolved.yaml, provenance.json, run.log,
//   probes/ground_acceleration.csv (the ground motion a_g(t) the solvers will
//   apply, sampled at output.probe_interval) and summary.json with its peaks,
//   so an input can be inspected before a long analysis is launched.
//
// Sample runs
//   build/bin/tankfsi_case cases/tank3d_fixed_roof_coarse/case.yaml
//   build/bin/tankfsi_case case.yaml --set excitation.time_scale=0.5 --prepare --output runs/check
//   build/bin/tankfsi_case --help
#include <iostream>

#include "common/excitation/ground_motion_factory.hpp"
#include "common/run/ground_motion_probe.hpp"
#include "common/run/program.hpp"

int main(int argc, char** argv) {
  const tankfsi::ProgramInfo program{
      "tankfsi_case",
      "checks a tankfsi case file and, with --prepare, writes its run folder and the ground motion it applies.",
      {"tankfsi_case cases/tank3d_fixed_roof_coarse/case.yaml",
       "tankfsi_case case.yaml --set excitation.time_scale=0.5 --prepare --output runs/check"},
      {"--prepare         write the run folder with the resolved case and probes/ground_acceleration.csv"},
      ""};  // never couples
  return tankfsi::run_program(
      argc, argv, program,
      [](const tankfsi::ProgramInputs& inputs) -> tankfsi::ProgramWork {
        // Reading the records here checks them (files, windows, rates) before
        // anything is written, also when only checking the case.
        std::shared_ptr<const tankfsi::GroundMotion> motion = tankfsi::make_ground_motion(inputs.config);
        return [motion](tankfsi::ProgramContext& context) -> nlohmann::json {
          if (!context.folder) {
            if (context.log.rank() == 0) std::cout << context.config.resolved_yaml();
            return {};
          }
          auto scope = context.timers.time("ground_motion");
          return tankfsi::write_ground_motion_probe(context, *motion);
        };
      },
      [](const tankfsi::CommandLine& cli) { return cli.has_flag("--prepare"); });
}
