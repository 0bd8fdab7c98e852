#pragma once
// The analyses of fem_solver running alone: static (one solve), modal (SLEPc)
// or dynamic (modal for the Rayleigh targets, then Newmark steps under the
// case's constant loads and ground motion). Returns the run's figures for
// summary.json. A dynamic step that fails stops the run with the step and
// time, after writing the last good state as a final snapshot.
#include <nlohmann/json.hpp>

#include "common/excitation/ground_motion.hpp"
#include "common/run/program.hpp"
#include "fem_solver/app/structure_case.hpp"

namespace tankfsi::fem {

nlohmann::json run_structure(ProgramContext& context, StructureCase structure_case, const GroundMotion& motion);

}  // namespace tankfsi::fem
