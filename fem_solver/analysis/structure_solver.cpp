#include "fem_solver/analysis/structure_solver.hpp"

#include "fem_solver/analysis/normal_added_mass.hpp"

#include "fem_solver/analysis/optional_stage.hpp"

#include <stdexcept>

namespace tankfsi::fem {
namespace {

Eigen::Vector3d translational_total(const NodalValues& values) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < values.size(); i += dofs_per_node)
    for (int k = 0; k < 3; ++k) sum(k) += values[i + static_cast<std::size_t>(k)];
  return sum;
}

}  // namespace

StructureSolver::StructureSolver(StructureSystem& system, RayleighCoefficients damping, const LoadSet& constant_loads,
                                 const GroundMotion& motion, TimeIntegrationRule rule, Kinematics kinematics)
    : system_(system), motion_(motion) {
  if (kinematics == Kinematics::corotational) {
    auto corotational = std::make_unique<CorotationalNewmark>(system, damping, rule);
    corotational_ = corotational.get();
    integrator_ = std::move(corotational);
  } else {
    integrator_ = std::make_unique<NewmarkIntegrator>(
        system.stiffness(), system.mass(), damping,
        [&system](Mat m) -> std::unique_ptr<LinearSolve> { return system.make_solver(m); }, rule);
  }
  SystemAssembler& assembler = system_.assembler();
  constant_load_ = assemble_loads(assembler, constant_loads);
  // Co-rotational: prescribed displacements are in the nodal state itself.
  if (!corotational_) assembler.add_prescribed_lift(constant_load_.get());
  petsc_check(VecAssemblyBegin(constant_load_.get()), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(constant_load_.get()), "VecAssemblyEnd");
  constant_total_ = translational_total(nodal_loads(system_.model(), constant_loads));
  external_load_ = assembler.create_vector();
  petsc_check(VecSet(external_load_.get(), 0.0), "VecSet");
  load_ = assembler.create_vector();
  for (int k = 0; k < 3; ++k) {
    mass_influence_[static_cast<std::size_t>(k)] = assembler.mass_times_influence(k);
    // The mass the ground load acts on: that of the free DOFs (supports move with the ground).
    PetscReal sum = 0.0;
    petsc_check(VecSum(mass_influence_[static_cast<std::size_t>(k)].get(), &sum), "VecSum");
    free_mass_(k) = sum;
  }
  build_load(0.0);
  PetscVector zero = assembler.create_vector();
  petsc_check(VecSet(zero.get(), 0.0), "VecSet");
  integrator_->initialise(zero.get(), zero.get(), load_.get());
}

void StructureSolver::set_interface(InterfaceMesh interface) {
  interface_ = std::move(interface);
  const DofMap& dofs = system_.dofs();
  interface_equations_.clear();
  std::vector<PetscInt> free;
  for (const int node : interface_.node_ids)
    for (int k = 0; k < 3; ++k) {
      interface_equations_.push_back(dofs.equation(node, k));
      if (interface_equations_.back() >= 0) free.push_back(interface_equations_.back());
    }
  // Every rank receives the interface's free values: a scatter of 3 values per
  // vertex instead of the whole state.
  IS from = nullptr;
  petsc_check(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(free.size()), free.data(), PETSC_COPY_VALUES, &from),
              "ISCreateGeneral");
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(free.size()), interface_gathered_.out()), "VecCreateSeq");
  const PetscErrorCode code =
      VecScatterCreate(integrator_->displacement(), from, interface_gathered_.get(), nullptr, interface_scatter_.out());
  ISDestroy(&from);
  petsc_check(code, "VecScatterCreate");
}

void StructureSolver::set_external_loads(std::span<const double> forces) {
  if (forces.size() != 3 * interface_.node_ids.size())
    throw std::invalid_argument("set_external_loads: " + std::to_string(forces.size()) + " values for " +
                                std::to_string(interface_.node_ids.size()) + " interface vertices (3 each)");
  NodalValues nodal(dofs_per_node * system_.model().mesh.nodes.size(), 0.0);
  for (std::size_t i = 0; i < interface_.node_ids.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      nodal[dofs_per_node * static_cast<std::size_t>(interface_.node_ids[i]) + k] = forces[3 * i + k];
  external_total_ = translational_total(nodal);
  system_.assembler().scatter(nodal, external_load_.get());
}

void StructureSolver::set_interface_added_mass(std::span<const double> matrix, std::span<const double> normals) {
  const std::size_t n = interface_.node_ids.size();
  if (matrix.size() != n * n || normals.size() != 3 * n)
    throw std::invalid_argument("set_interface_added_mass: " + std::to_string(matrix.size()) + " entries and " +
                                std::to_string(normals.size()) + " normal values for " + std::to_string(n) +
                                " interface vertices");
  Mat k = system_.stiffness();
  PetscInt local_rows = 0, local_columns = 0, rows = 0, columns = 0, first = 0, end = 0;
  petsc_check(MatGetLocalSize(k, &local_rows, &local_columns), "MatGetLocalSize");
  petsc_check(MatGetSize(k, &rows, &columns), "MatGetSize");
  petsc_check(MatGetOwnershipRange(k, &first, &end), "MatGetOwnershipRange");
  // Every free interface translation couples with every other: each interface
  // row of this rank has them all, split into this rank's columns and the rest.
  PetscInt own_columns = 0, other_columns = 0;
  for (const PetscInt e : interface_equations_)
    if (e >= 0) ++(e >= first && e < end ? own_columns : other_columns);
  // Other rows hold their (zero) diagonal: M + M_a is then M_a with M on its diagonal.
  std::vector<PetscInt> diagonal_count(static_cast<std::size_t>(local_rows), 1);
  std::vector<PetscInt> off_diagonal_count(static_cast<std::size_t>(local_rows), 0);
  for (const PetscInt e : interface_equations_)
    if (e >= first && e < end) {
      diagonal_count[static_cast<std::size_t>(e - first)] = own_columns;
      off_diagonal_count[static_cast<std::size_t>(e - first)] = other_columns;
    }
  petsc_check(MatCreateAIJ(PetscObjectComm(reinterpret_cast<PetscObject>(k)), local_rows, local_columns, rows, columns, 0,
                           diagonal_count.data(), 0, off_diagonal_count.data(), added_mass_.out()),
              "MatCreateAIJ");
  for (PetscInt row = first; row < end; ++row)
    petsc_check(MatSetValue(added_mass_.get(), row, row, 0.0, INSERT_VALUES), "MatSetValue");
  std::vector<PetscInt> column_index;
  std::vector<PetscScalar> values;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d n_i(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
    for (int a = 0; a < 3; ++a) {
      const PetscInt row = interface_equations_[3 * i + static_cast<std::size_t>(a)];
      if (row < first || row >= end) continue;  // another rank's row, or a supported DOF
      column_index.clear();
      values.clear();
      for (std::size_t j = 0; j < n; ++j)
        for (int b = 0; b < 3; ++b) {
          const PetscInt column = interface_equations_[3 * j + static_cast<std::size_t>(b)];
          if (column < 0) continue;
          column_index.push_back(column);
          values.push_back(n_i[a] * matrix[i * n + j] * normals[3 * j + static_cast<std::size_t>(b)]);
        }
      petsc_check(MatSetValues(added_mass_.get(), 1, &row, static_cast<PetscInt>(column_index.size()),
                               column_index.data(), values.data(), INSERT_VALUES),
                  "MatSetValues");
    }
  }
  petsc_check(MatAssemblyBegin(added_mass_.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(added_mass_.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  set_normal_added_mass(matrix, normals);
}

void StructureSolver::set_normal_added_mass(std::span<const double> matrix, std::span<const double> normals) {
  // N: row i takes vertex i's free translations onto its normal; A: the operator,
  // rows and columns laid out as N's rows (normal_added_mass.hpp).
  const auto n = static_cast<PetscInt>(interface_.node_ids.size());
  Mat k = system_.stiffness();
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(k));
  PetscInt local_columns = 0, columns = 0;
  petsc_check(MatGetLocalSize(k, nullptr, &local_columns), "MatGetLocalSize");
  petsc_check(MatGetSize(k, nullptr, &columns), "MatGetSize");
  PetscMatrix normal_map;
  petsc_check(MatCreateAIJ(comm, PETSC_DECIDE, local_columns, n, columns, 3, nullptr, 3, nullptr, normal_map.out()),
              "MatCreateAIJ");
  PetscInt first = 0, end = 0;
  petsc_check(MatGetOwnershipRange(normal_map.get(), &first, &end), "MatGetOwnershipRange");
  for (PetscInt i = first; i < end; ++i)
    for (std::size_t a = 0; a < 3; ++a) {
      const PetscInt column = interface_equations_[3 * static_cast<std::size_t>(i) + a];
      if (column >= 0)
        petsc_check(MatSetValue(normal_map.get(), i, column, normals[3 * static_cast<std::size_t>(i) + a],
                                INSERT_VALUES),
                    "MatSetValue");
    }
  petsc_check(MatAssemblyBegin(normal_map.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(normal_map.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  PetscMatrix operator_matrix;
  petsc_check(MatCreateDense(comm, end - first, end - first, n, n, nullptr, operator_matrix.out()), "MatCreateDense");
  std::vector<PetscInt> all_columns(static_cast<std::size_t>(n));
  for (PetscInt j = 0; j < n; ++j) all_columns[static_cast<std::size_t>(j)] = j;
  for (PetscInt i = first; i < end; ++i)
    petsc_check(MatSetValues(operator_matrix.get(), 1, &i, n, all_columns.data(),
                             matrix.data() + static_cast<std::size_t>(i) * static_cast<std::size_t>(n), INSERT_VALUES),
                "MatSetValues");
  petsc_check(MatAssemblyBegin(operator_matrix.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(operator_matrix.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  added_mass_product_ = make_normal_added_mass_product(normal_map.get(), operator_matrix.get());
  integrator_->set_added_mass(added_mass_.get(), added_mass_product_.get(),
                             make_normal_added_mass_inertia(normal_map.get(), matrix, system_.mass()));
}

void StructureSolver::balance_acceleration() {
  const auto stage = time_stage(system_.timers(), "shell_balance");
  build_load(time_);
  integrator_->set_load(load_.get());
  mark_state_changed();
}

void StructureSolver::start_at_equilibrium() {
  build_load(time_);
  if (corotational_) {
    corotational_->equilibrate(load_.get());
    mark_state_changed();
    return;
  }
  PetscVector u = system_.assembler().create_vector();
  {
    const auto solver = system_.make_solver(system_.stiffness());
    solver->solve(load_.get(), u.get());
  }
  PetscVector zero = system_.assembler().create_vector();
  petsc_check(VecSet(zero.get(), 0.0), "VecSet");
  integrator_->initialise(u.get(), zero.get(), load_.get());
  mark_state_changed();
}

void StructureSolver::build_load(double t) {
  // F = F_constant + F_external - sum_k a_g,k(t) M iota_k
  const Eigen::Vector3d ground = motion_.acceleration(t);
  petsc_check(VecWAXPY(load_.get(), 1.0, constant_load_.get(), external_load_.get()), "VecWAXPY");
  for (int k = 0; k < 3; ++k)
    if (ground(k) != 0.0)
      petsc_check(VecAXPY(load_.get(), -ground(k), mass_influence_[static_cast<std::size_t>(k)].get()), "VecAXPY");
}

void StructureSolver::advance(double dt) {
  const auto stage = time_stage(system_.timers(), "shell_step");
  build_load(time_ + dt);
  try {
    integrator_->step(dt, load_.get());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("structure step " + std::to_string(steps_ + 1) + " to t = " + std::to_string(time_ + dt) +
                             " s failed: " + e.what());
  }
  time_ += dt;
  ++steps_;
  mark_state_changed();
}

void StructureSolver::save(Checkpoint& checkpoint) const {
  integrator_->save(checkpoint.state);
  checkpoint.time = time_;
  checkpoint.steps = steps_;
}

void StructureSolver::restore(const Checkpoint& checkpoint) {
  integrator_->restore(checkpoint.state);
  time_ = checkpoint.time;
  steps_ = checkpoint.steps;
  mark_state_changed();
}

void StructureSolver::mark_state_changed() {
  for (GatheredState* state : {&displacement_, &velocity_, &acceleration_}) state->current = false;
}

const NodalValues& StructureSolver::gathered(GatheredState& state, Vec values, double prescribed_scale) const {
  if (!state.current) system_.assembler().gather(values, prescribed_scale, state.values);
  state.current = true;
  return state.values;
}

// Displacements carry the prescribed values of constrained DOFs; velocities
// and accelerations are zero there (prescribed displacements are constant).
const NodalValues& StructureSolver::displacement() const {
  return gathered(displacement_, integrator_->displacement(), 1.0);
}
const NodalValues& StructureSolver::velocity() const { return gathered(velocity_, integrator_->velocity(), 0.0); }
const NodalValues& StructureSolver::acceleration() const {
  return gathered(acceleration_, integrator_->acceleration(), 0.0);
}

double StructureSolver::largest_displacement() const {
  return system_.assembler().largest_translation(integrator_->displacement(), 1.0);
}

std::vector<double> StructureSolver::interface_values(Vec values, double prescribed_scale) const {
  std::vector<double> out;
  out.reserve(interface_equations_.size());
  if (!interface_scatter_) return out;
  petsc_check(VecScatterBegin(interface_scatter_.get(), values, interface_gathered_.get(), INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterBegin");
  petsc_check(VecScatterEnd(interface_scatter_.get(), values, interface_gathered_.get(), INSERT_VALUES, SCATTER_FORWARD),
              "VecScatterEnd");
  const PetscScalar* x = nullptr;
  petsc_check(VecGetArrayRead(interface_gathered_.get(), &x), "VecGetArrayRead");
  std::size_t next = 0;
  for (std::size_t i = 0; i < interface_equations_.size(); ++i) {
    const int node = interface_.node_ids[i / 3];
    const int component = static_cast<int>(i % 3);
    out.push_back(interface_equations_[i] >= 0 ? x[next++] : prescribed_scale * system_.dofs().prescribed(node, component));
  }
  petsc_check(VecRestoreArrayRead(interface_gathered_.get(), &x), "VecRestoreArrayRead");
  return out;
}

std::vector<double> StructureSolver::interface_displacements() const {
  return interface_values(integrator_->displacement(), 1.0);
}
std::vector<double> StructureSolver::interface_velocities() const { return interface_values(integrator_->velocity(), 0.0); }

Eigen::Vector3d StructureSolver::total_external_force() const {
  return constant_total_ + external_total_ - free_mass_.cwiseProduct(motion_.acceleration(time_));
}

NodalValues StructureSolver::support_forces() const {
  if (corotational_) return corotational_->support_forces();
  return system_.assembler().reactions(displacement(), velocity(), integrator_->damping().beta);
}

}  // namespace tankfsi::fem
