#pragma once
// A CouplingRestartState (coupling/participant.hpp) in a checkpoint file
// (common/run/checkpoint_series.hpp), under one group:
//
//   arrays/<name>   the state's arrays; rows/<name> how many values each rank wrote
//   reports         the accepted windows (n×13: window, start, end, iterations,
//                   converged, displacement and force residuals, impulse given
//                   x y z, impulse applied x y z)
//   history_numbers the acceleration's numbers
//   attributes: window, window_start_s
//
// `replicated`: the arrays are the same on every rank (the fluid side's whole
// interface): rank 0 writes them and every rank reads them whole, whatever
// the rank counts. Otherwise (the structure side) each rank writes its part
// and reads it back on as many ranks. Reports and numbers are the same on
// every rank of either side: rank 0 writes them.
#include <string>

#include "common/io/hdf5_file.hpp"
#include "coupling/participant.hpp"

namespace tankfsi::coupling {

/// Collective over the file's ranks.
void write_restart_state(Hdf5File& file, const std::string& group, const CouplingRestartState& state, bool replicated);
/// Collective; throws std::runtime_error when the group is missing or was
/// written on another rank count (distributed arrays).
CouplingRestartState read_restart_state(const Hdf5File& file, const std::string& group, bool replicated);

}  // namespace tankfsi::coupling
