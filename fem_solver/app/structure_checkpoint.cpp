#include "fem_solver/app/structure_checkpoint.hpp"

#include <array>
#include <utility>

#include "common/config/config_error.hpp"

namespace tankfsi::fem {
namespace {

const Origin restart_origin{"--restart", 0};

/// f, the load at the state's time, only the generalized-alpha rule reads;
/// checkpoints written before it was kept have none (read_structure_state).
std::array<std::pair<const char*, Vec>, 7> newmark_vectors(const StructureSolver::Checkpoint& c) {
  return {{{"u", c.state.u.get()}, {"v", c.state.v.get()}, {"a", c.state.a.get()},
           {"ku", c.state.ku.get()}, {"kv", c.state.kv.get()}, {"ka", c.state.ka.get()}, {"f", c.state.f.get()}}};
}

}  // namespace

void write_structure_state(Hdf5File& file, const StructureSolver& solver, const nlohmann::json& run_state) {
  StructureSolver::Checkpoint state;
  solver.save(state);
  for (const auto& [name, vector] : newmark_vectors(state)) {
    PetscInt local = 0;
    petsc_check(VecGetLocalSize(vector, &local), "VecGetLocalSize");
    const PetscScalar* values = nullptr;
    petsc_check(VecGetArrayRead(vector, &values), "VecGetArrayRead");
    const std::vector<double> rows(values, values + local);
    petsc_check(VecRestoreArrayRead(vector, &values), "VecRestoreArrayRead");
    file.write_distributed_1d(std::string("/structure/newmark/") + name, std::span<const double>(rows));
  }
  file.write_attribute("/structure", "time_s", state.time);
  file.write_attribute("/structure", "steps", static_cast<std::int64_t>(state.steps));
  file.write_attribute("/structure", "run_state", run_state.dump());
}

nlohmann::json read_structure_state(MPI_Comm comm, const RestartPoint& point, StructureSolver& solver) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (point.ranks != size)
    throw ConfigError(restart_origin, "", point.path.string() + " was written on " + std::to_string(point.ranks) +
                                              " structure rank(s); fem_solver continues only on as many, not " +
                                              std::to_string(size));
  const Hdf5File file(comm, point.path, FileMode::read);
  if (!file.exists("/structure/newmark/u"))
    throw ConfigError(restart_origin, "", point.path.string() + " holds no structure state");
  StructureSolver::Checkpoint state;
  solver.save(state);  // vectors of the right layout, overwritten below
  for (const auto& [name, vector] : newmark_vectors(state)) {
    const std::string dataset = std::string("/structure/newmark/") + name;
    if (!file.exists(dataset) && std::string(name) == "f") {
      if (solver.integrator().rule().alpha_f == 0.0) continue;  // an older checkpoint: average acceleration does not read f
      throw ConfigError(restart_origin, "", point.path.string() +
                                                " holds no load of its last step (written by an older fem_solver): "
                                                "the generalized-alpha rule (structure.time_integration) cannot continue it");
    }
    PetscInt local = 0;
    petsc_check(VecGetLocalSize(vector, &local), "VecGetLocalSize");
    const RowBlock block = rank_order_rows(comm, local);
    if (file.shape(dataset).rows != block.total)
      throw ConfigError(restart_origin, "", point.path.string() + " holds " + std::to_string(file.shape(dataset).rows) +
                                                " equations, this structure has " + std::to_string(block.total));
    const std::vector<double> rows = file.read_rows_double(dataset, block.first, block.local);
    PetscScalar* values = nullptr;
    petsc_check(VecGetArray(vector, &values), "VecGetArray");
    std::copy(rows.begin(), rows.end(), values);
    petsc_check(VecRestoreArray(vector, &values), "VecRestoreArray");
  }
  state.time = file.read_double_attribute("/structure", "time_s");
  state.steps = file.read_int64_attribute("/structure", "steps");
  solver.restore(state);
  return nlohmann::json::parse(file.read_string_attribute("/structure", "run_state"));
}

}  // namespace tankfsi::fem
