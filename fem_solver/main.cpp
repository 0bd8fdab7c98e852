// fem_solver: the structure program — MITC shell finite elements for thin
// tanks (METHOD.md §3): linear static, modal (SLEPc) and Newmark dynamic
// analyses, MPI-parallel. Runs alone with prescribed loads and ground motion;
// later the partner of sph_solver through the coupling library.
//
//   build/bin/fem_solver cases/shell_benchmarks/scordelis_lo/case.yaml
//   mpirun -np 2 build/bin/fem_solver cases/tank3d_dry/case.yaml --output runs/dry
//   build/bin/fem_solver case.yaml -shell_ksp_type cg -shell_pc_type gamg -log_view
//   build/bin/fem_solver --help
#include <memory>
#include <stdexcept>

#include "common/excitation/ground_motion_factory.hpp"
#include "common/run/petsc_defaults.hpp"
#include "common/run/program.hpp"
#include "fem_solver/app/structure_case.hpp"
#include "fem_solver/app/structure_coupling.hpp"
#include "fem_solver/app/structure_run.hpp"

int main(int argc, char** argv) {
  const tankfsi::ProgramInfo program{
      "fem_solver",
      "MITC4/MITC3 shell finite elements: static, modal (SLEPc) and Newmark dynamic analyses.",
      {"fem_solver cases/shell_benchmarks/scordelis_lo/case.yaml --set structure.mesh.divisions=[8,8]",
       "mpirun -np 2 fem_solver cases/tank3d_dry/case.yaml", "fem_solver case.yaml -shell_ksp_type cg -shell_pc_type gamg",
       "fem_solver case.yaml -eps_monitor -log_view"},
      {},
      "structure",
      true};  // restarts only on the checkpoint's rank count (structure_checkpoint.hpp)
  return tankfsi::run_program(argc, argv, program, [](const tankfsi::ProgramInputs& inputs) -> tankfsi::ProgramWork {
    auto structure_case =
        std::make_shared<tankfsi::fem::StructureCase>(tankfsi::fem::read_structure_case(inputs.config));
    try {
      tankfsi::apply_default_petsc_options(structure_case->solver_options);
    } catch (const std::invalid_argument& e) {
      throw inputs.config.error_at("structure.solver_options", e.what());
    }
    if (inputs.partner != MPI_COMM_NULL) tankfsi::fem::check_coupled_structure_case(inputs.config, structure_case->mesh);
    std::shared_ptr<const tankfsi::GroundMotion> motion = tankfsi::make_ground_motion(inputs.config);
    return [structure_case, motion](tankfsi::ProgramContext& context) -> nlohmann::json {
      return tankfsi::fem::run_structure(context, std::move(*structure_case), *motion);
    };
  });
}
