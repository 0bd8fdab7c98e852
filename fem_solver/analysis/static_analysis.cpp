#include "fem_solver/analysis/static_analysis.hpp"

#include "fem_solver/analysis/optional_stage.hpp"

namespace tankfsi::fem {

StaticResult solve_static(StructureSystem& system, const LoadSet& loads) {
  SystemAssembler& assembler = system.assembler();
  PetscVector rhs = assemble_loads(assembler, loads);
  assembler.add_prescribed_lift(rhs.get());
  petsc_check(VecAssemblyBegin(rhs.get()), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(rhs.get()), "VecAssemblyEnd");
  const auto solver = system.make_solver(system.stiffness());
  PetscVector u = assembler.create_vector();
  {
    const auto stage = time_stage(system.timers(), "shell_solve");
    solver->solve(rhs.get(), u.get());
  }
  StaticResult result;
  result.displacement = assembler.gather(u.get(), 1.0);
  result.reactions = assembler.reactions(result.displacement, result.displacement, 0.0);
  result.solver = solver->description();
  result.iterations = solver->last_iterations();
  return result;
}

}  // namespace tankfsi::fem
