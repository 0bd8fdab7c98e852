#pragma once
// The fluid's part of a checkpoint (common/run/checkpoint_series.hpp), group
// /fluid of the file:
//
//   particles/{id, position (n×3), velocity (n×3), mass, pressure}
//       every particle, rows in rank order (rank 0's owned ones, then rank 1's...)
//   rank_rows      how many rows each rank wrote (one per rank)
//   decomposition_cuts   axis and position of every cut of the decomposition
//   attributes: steps, removed_count, removed_volume, and run_state (JSON: what
//   the time loop keeps — next output times, the step controller's last
//   speed and pressure, the running statistics).
//   pressure_hierarchy/{ids, row_lengths, columns, values, rank_rows,
//       rank_entries}, attributes first_iterations, rebuild: the pressure
//       solver's kept hierarchy's rows (fluid.ppe.keep_hierarchy;
//       kept_hierarchy.hpp), when there is one.
//
// That is the whole state a step starts from: the walls are the case's (a
// coupled run's moving ones are put where the coupling says at each step), the
// PPE starts from the particles' pressures (and the kept hierarchy, built
// again from its rows), and nothing is random. Read on as
// many ranks, each rank takes its own rows back with the cuts: the run goes on
// bit for bit. On another rank count each rank takes an even slice of the
// rows and the particles are balanced anew: the same physics, with sums in
// another order (round-off), and PPE solutions that differ within the KSP's
// tolerance.
#include <nlohmann/json.hpp>

#include <optional>
#include <vector>

#include "common/io/hdf5_file.hpp"
#include "common/run/checkpoint_series.hpp"
#include "sph_solver/isph/fluid_solver.hpp"

namespace tankfsi::sph {

/// Collective: writes the solver's state and `run_state` under /fluid.
void write_fluid_state(Hdf5File& file, const FluidSolver& solver, const nlohmann::json& run_state);

struct FluidRestart {
  FluidSolver::Checkpoint state;  ///< this rank's particles and the counters
  std::optional<std::vector<double>> cuts;  ///< none when the rank count changed
  nlohmann::json run_state;
};

/// Collective: reads /fluid of the checkpoint at `point`.
FluidRestart read_fluid_state(MPI_Comm comm, const RestartPoint& point);

}  // namespace tankfsi::sph
