#pragma once
// Runs the partitioned two-mass oscillator (coupling/examples) on a split
// world and measures it against the closed form.
#include <vector>

#include "coupling/examples/oscillator_partner.hpp"
#include "partner_split.hpp"

namespace tankfsi::coupling::testing {

struct OscillatorResult {
  double max_error = 0.0;  ///< over both sides, windows and vertices: |x - exact| / x1(0)
  std::vector<WindowReport> reports;
  long long iterations = 0;  ///< coupling iterations over all windows
  long long windows = 0;
};

struct OscillatorRun {
  CouplingSettings settings;
  examples::OscillatorParameters parameters;
  int vertices = 12;
  double fluid_step_fraction = 0.3;  ///< fluid sub-step / dt_c (the last one is shortened)
  double structure_step_fraction = 0.25;

  OscillatorResult run(const PartnerSplit& split) const {
    Participant p(split.side, settings, split.local, split.partner);
    examples::OscillatorPartner side(split.side, split.local, parameters, vertices);
    side.declare(p);
    p.exchange_interface();
    side.start(p);
    p.initialize();
    OscillatorResult result;
    const double fraction = split.side == Side::fluid ? fluid_step_fraction : structure_step_fraction;
    const double error = side.run(p, fraction * settings.time_window);
    p.finalize();
    result.reports = p.window_reports();
    for (const auto& r : result.reports) result.iterations += r.iterations;
    result.windows = static_cast<long long>(result.reports.size());
    MPI_Allreduce(&error, &result.max_error, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return result;
  }
};

}  // namespace tankfsi::coupling::testing
