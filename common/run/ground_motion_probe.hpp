#pragma once
// probes/ground_acceleration.csv: the ground motion a_g(t) a run applies, sampled
// at output.probe_interval from 0 to end_time (else the motion's own duration),
// so that every run folder holds the input its results answer to.
#include <nlohmann/json.hpp>

#include "common/excitation/ground_motion.hpp"
#include "common/run/program.hpp"

namespace tankfsi {

/// Writes the file (rank 0) and returns its peaks, as summary.json's "excitation"
/// entry. Collective only in that every rank returns the same value.
nlohmann::json write_ground_motion_probe(ProgramContext& context, const GroundMotion& motion);

}  // namespace tankfsi
