#pragma once
// The structure's part of a checkpoint (common/run/checkpoint_series.hpp),
// group /structure of the file:
//
//   newmark/{u, v, a, ku, kv, ka}   the Newmark state (METHOD.md §3) and the
//       stiffness products carried with it (newmark.hpp), each rank's rows of
//       the distributed vectors in rank order
//   attributes: time_s, steps, run_state (JSON: the time loop's next output
//   times and peaks)
//
// With the same ranks the equations are numbered as before (the partition is
// a deterministic function of mesh and rank count), each rank takes its rows
// back, and the run goes on bit for bit; the factorisation of K_eff is made
// anew from the same matrix. Another rank count is refused: the state would
// need renumbering (not implemented).
#include <nlohmann/json.hpp>

#include "common/io/hdf5_file.hpp"
#include "common/run/checkpoint_series.hpp"
#include "fem_solver/analysis/structure_solver.hpp"

namespace tankfsi::fem {

/// Collective: writes the solver's state and `run_state` under /structure.
void write_structure_state(Hdf5File& file, const StructureSolver& solver, const nlohmann::json& run_state);

/// Collective: puts the state of the checkpoint at `point` into `solver` and
/// returns its run_state. Throws ConfigError (origin --restart) when the
/// checkpoint was written on another rank count or for another system size.
nlohmann::json read_structure_state(MPI_Comm comm, const RestartPoint& point, StructureSolver& solver);

}  // namespace tankfsi::fem
