// sph_solver: the fluid program — incompressible SPH with triangle-patch walls
// (METHOD.md §1-2). Runs alone with rigid walls; later the partner of fem_solver.
//
//   build/bin/sph_solver cases/dam_break_2d/case.yaml
//   mpirun -np 2 build/bin/sph_solver cases/hydrostatic_2d/case.yaml --output runs/h2d
//   build/bin/sph_solver --help
#include <memory>

#include "common/excitation/ground_motion_factory.hpp"
#include "common/run/program.hpp"
#include "sph_solver/app/fluid_case.hpp"
#include "sph_solver/app/fluid_coupling.hpp"
#include "sph_solver/app/fluid_run.hpp"

int main(int argc, char** argv) {
  const tankfsi::ProgramInfo program{
      "sph_solver",
      "incompressible SPH fluid solver with triangle-patch walls (rigid walls when run alone).",
      {"sph_solver cases/dam_break_2d/case.yaml", "mpirun -np 2 sph_solver case.yaml --set fluid.spacing=0.02",
       "sph_solver case.yaml -ppe_ksp_monitor -log_view"},
      {},
      "fluid"};
  return tankfsi::run_program(argc, argv, program, [](const tankfsi::ProgramInputs& inputs) -> tankfsi::ProgramWork {
    auto fluid_case = std::make_shared<tankfsi::sph::FluidCase>(tankfsi::sph::read_fluid_case(inputs.config));
    if (inputs.partner != MPI_COMM_NULL) tankfsi::sph::check_coupled_fluid_case(inputs.config);
    std::shared_ptr<const tankfsi::GroundMotion> motion = tankfsi::make_ground_motion(inputs.config);
    return [fluid_case, motion](tankfsi::ProgramContext& context) -> nlohmann::json {
      return tankfsi::sph::run_fluid(context, std::move(*fluid_case), *motion);
    };
  });
}
