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
#include <cmath>
#include <iostream>

#include "common/excitation/ground_motion_factory.hpp"
#include "common/io/probe_file.hpp"
#include "common/run/program.hpp"

namespace {

// Samples a_g(t) over the run (end_time, else the motion's own duration) into
// probes/ground_acceleration.csv and returns its peaks for summary.json.
nlohmann::json write_ground_motion_probe(tankfsi::ProgramContext& context, const tankfsi::GroundMotion& motion) {
  const auto& config = context.config;
  const double interval = config.real("output.probe_interval");
  const double end = config.has("end_time") ? config.real("end_time") : motion.duration();
  const auto steps = static_cast<long>(std::floor(end / interval + 1e-9));

  tankfsi::ProbeFile probe(context.folder->probes() / "ground_acceleration.csv",
                           {"ax_m_s2", "ay_m_s2", "az_m_s2"}, config.real("output.field_interval"));
  Eigen::Vector3d peak = Eigen::Vector3d::Zero();
  Eigen::Vector3d peak_time = Eigen::Vector3d::Zero();
  for (long k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * interval;
    const Eigen::Vector3d a = motion.acceleration(t);
    probe.append(t, {a.data(), 3});
    for (int c = 0; c < 3; ++c)
      if (std::abs(a[c]) > peak[c]) {
        peak[c] = std::abs(a[c]);
        peak_time[c] = t;
      }
  }
  probe.flush();
  context.log.info("ground motion ", config.text("excitation.type"), ": peak |a| = (", peak.x(), ", ", peak.y(), ", ",
                   peak.z(), ") m/s^2 over ", end, " s");
  return {{"excitation",
           {{"type", config.text("excitation.type")},
            {"sampled_until_s", end},
            {"peak_acceleration_m_s2", {peak.x(), peak.y(), peak.z()}},
            {"peak_time_s", {peak_time.x(), peak_time.y(), peak_time.z()}}}}};
}

}  // namespace

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
          return write_ground_motion_probe(context, *motion);
        };
      },
      [](const tankfsi::CommandLine& cli) { return cli.has_flag("--prepare"); });
}
