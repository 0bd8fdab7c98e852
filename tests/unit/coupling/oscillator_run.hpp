#pragma once
// Runs the partitioned two-mass oscillator (coupling/examples) on a split
// world and measures it against the closed form.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "coupling/examples/two_mass_oscillator.hpp"
#include "coupling/participant.hpp"
#include "partner_split.hpp"

namespace tankfsi::coupling::testing {

struct OscillatorResult {
  double max_error = 0.0;  ///< max over windows and vertices of |x - exact| / x1(0), own side's mass
  std::vector<WindowReport> reports;
  long long iterations = 0;  ///< coupling iterations over all windows
  long long windows = 0;
};

struct OscillatorRun {
  CouplingSettings settings;
  examples::OscillatorParameters parameters;
  int vertices = 12;
  double fluid_step_fraction = 0.3;      ///< fluid sub-step / dt_c (the last one is shortened)
  double structure_step_fraction = 0.25;

  [[nodiscard]] std::vector<std::int64_t> vertex_ids() const {
    std::vector<std::int64_t> ids;
    for (int k = 0; k < vertices; ++k) ids.push_back(1000 + 3 * k);
    return ids;
  }

  OscillatorResult run(const PartnerSplit& split) const {
    Participant p(split.side, settings, split.local, split.partner);
    int rank = 0, size = 1;
    MPI_Comm_rank(split.local, &rank);
    MPI_Comm_size(split.local, &size);
    const auto ids = vertex_ids();
    // Structure rank s declares vertices k = s, s + B, ...: every fluid slice
    // then talks to every structure rank.
    std::vector<std::int64_t> mine;
    if (split.side == Side::structure) {
      std::vector<double> coordinates;
      std::vector<std::array<std::int64_t, 3>> triangles;
      for (int k = rank; k < vertices; k += size) {
        mine.push_back(ids[static_cast<std::size_t>(k)]);
        coordinates.insert(coordinates.end(), {0.1 * k, 0.0, 0.0});
        if (k + 2 < vertices)
          triangles.push_back({ids[static_cast<std::size_t>(k)], ids[static_cast<std::size_t>(k + 1)],
                               ids[static_cast<std::size_t>(k + 2)]});
      }
      p.set_interface(mine, coordinates, triangles);
    }
    p.exchange_interface();
    const std::vector<std::int64_t>& held = p.interface_mesh().ids;  // fluid: all, sorted; structure: mine
    const std::size_t n = held.size();
    // The fluid integrates vertex k on fluid rank k mod A and writes zero elsewhere.
    std::vector<bool> integrated(n, true);
    if (split.side == Side::fluid)
      for (std::size_t k = 0; k < n; ++k) integrated[k] = static_cast<int>(k % static_cast<std::size_t>(size)) == rank;
    std::vector<examples::NewmarkDof> dofs(n);
    std::vector<examples::OscillatorParameters> params(n);
    std::vector<double> values(3 * n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      params[k] = parameters.at_vertex(held[k]);
      auto& d = dofs[k];
      if (split.side == Side::fluid) {
        d.mass = params[k].m1;
        d.stiffness = params[k].k1 + params[k].kc;
        d.start(params[k].x1_initial, 0.0, 0.0);  // kc x2(0) = 0
        if (integrated[k]) values[3 * k] = params[k].kc * params[k].x1_initial;
      } else {
        d.mass = params[k].m2;
        d.stiffness = params[k].k2;
        d.start(0.0, 0.0, params[k].kc * params[k].x1_initial);
      }
    }
    if (split.side == Side::fluid) p.write(Field::force, values);
    else p.write(Field::displacement, values);
    p.initialize();

    OscillatorResult result;
    std::vector<examples::NewmarkDof> saved = dofs;
    const double own_step = (split.side == Side::fluid ? fluid_step_fraction : structure_step_fraction) * settings.time_window;
    std::vector<double> start(3 * n), end(3 * n);
    while (p.is_ongoing()) {
      if (p.requires_writing_checkpoint()) saved = dofs;
      const double dt = std::min(own_step, p.max_time_step());
      if (split.side == Side::fluid) {
        p.read(Field::displacement, 0.0, start);
        p.read(Field::displacement, dt, end);
        for (std::size_t k = 0; k < n; ++k) {
          const double x1_old = dofs[k].u;
          dofs[k].step(dt, params[k].kc * end[3 * k]);
          // The force over the step: trapezoidal, as Newmark integrates it.
          values[3 * k] = integrated[k] ? params[k].kc * (0.5 * (x1_old + dofs[k].u) - 0.5 * (start[3 * k] + end[3 * k])) : 0.0;
        }
        p.write(Field::force, values);
      } else {
        p.read(Field::force, dt, end);
        for (std::size_t k = 0; k < n; ++k) {
          dofs[k].step(dt, end[3 * k]);
          values[3 * k] = dofs[k].u;
        }
        p.write(Field::displacement, values);
      }
      p.advance(dt);
      if (p.requires_reading_checkpoint()) dofs = saved;
      if (p.window_completed()) {
        const double t = p.time();
        for (std::size_t k = 0; k < n; ++k) {
          if (!integrated[k]) continue;
          const Eigen::Vector2d exact = examples::oscillator_exact(params[k], t);
          const double x = split.side == Side::fluid ? exact[0] : exact[1];
          result.max_error = std::max(result.max_error, std::abs(dofs[k].u - x) / params[k].x1_initial);
          if (!std::isfinite(dofs[k].u)) result.max_error = std::numeric_limits<double>::infinity();
        }
      }
    }
    p.finalize();
    result.reports = p.window_reports();
    for (const auto& r : result.reports) result.iterations += r.iterations;
    result.windows = static_cast<long long>(result.reports.size());
    // Both sides' largest error on every rank of the world.
    double error = result.max_error;
    MPI_Allreduce(&error, &result.max_error, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return result;
  }
};

}  // namespace tankfsi::coupling::testing
