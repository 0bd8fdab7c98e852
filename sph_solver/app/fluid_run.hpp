#pragma once
// The time loop of sph_solver running alone (rigid walls): steps the FluidSolver
// from t = 0 to end_time, samples the probes every probe interval, writes particle
// and wall snapshots every field interval, and returns the run's figures for
// summary.json. A step that fails (PPE divergence, non-finite velocity, a fixed
// time step beyond the stability limit) stops the run with the step and time, after
// writing the last good state as a final snapshot.
#include <nlohmann/json.hpp>

#include "common/excitation/ground_motion.hpp"
#include "common/run/program.hpp"
#include "sph_solver/app/fluid_case.hpp"

namespace tankfsi::sph {

nlohmann::json run_fluid(ProgramContext& context, FluidCase fluid_case, const GroundMotion& motion);

}  // namespace tankfsi::sph
