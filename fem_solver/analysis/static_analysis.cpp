#include "fem_solver/analysis/static_analysis.hpp"

#include "fem_solver/analysis/corotational_newmark.hpp"
#include "fem_solver/analysis/optional_stage.hpp"

#include <stdexcept>
#include <string>

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

StaticResult solve_static_corotational(StructureSystem& system, const LoadSet& loads, int load_steps) {
  SystemAssembler& assembler = system.assembler();
  // No lift: prescribed displacements are in the nodal state the elements see.
  PetscVector total = assemble_loads(assembler, loads);
  petsc_check(VecAssemblyBegin(total.get()), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(total.get()), "VecAssemblyEnd");
  CorotationalNewmark integrator(system, RayleighCoefficients{});
  PetscVector load = assembler.create_vector();
  StaticResult result;
  {
    const auto stage = time_stage(system.timers(), "shell_solve");
    for (int k = 1; k <= load_steps; ++k) {
      petsc_check(VecCopy(total.get(), load.get()), "VecCopy");
      petsc_check(VecScale(load.get(), static_cast<double>(k) / load_steps), "VecScale");
      try {
        result.iterations += integrator.equilibrate(load.get());
      } catch (const std::runtime_error& e) {
        throw std::runtime_error("load step " + std::to_string(k) + " of " + std::to_string(load_steps) + ": " +
                                 e.what() + " (more structure.load_steps may help)");
      }
    }
  }
  result.displacement = assembler.gather(integrator.displacement(), 1.0);
  result.reactions = integrator.support_forces();
  result.solver = "co-rotational Newton, " + std::to_string(load_steps) + " load steps, " +
                  std::to_string(result.iterations) + " iterations";
  return result;
}

}  // namespace tankfsi::fem
