#include "sph_solver/app/fluid_checkpoint.hpp"

#include <stdexcept>

namespace tankfsi::sph {
namespace {

std::vector<double> flatten(const std::vector<Eigen::Vector3d>& vectors) {
  std::vector<double> values;
  values.reserve(3 * vectors.size());
  for (const auto& v : vectors) values.insert(values.end(), v.data(), v.data() + 3);
  return values;
}

std::vector<Eigen::Vector3d> vectors_of(const std::vector<double>& values) {
  std::vector<Eigen::Vector3d> vectors(values.size() / 3);
  for (std::size_t i = 0; i < vectors.size(); ++i) vectors[i] = Eigen::Vector3d(values[3 * i], values[3 * i + 1], values[3 * i + 2]);
  return vectors;
}

}  // namespace

void write_fluid_state(Hdf5File& file, const FluidSolver& solver, const nlohmann::json& run_state) {
  const Particles& p = solver.particles();
  file.write_distributed_1d("/fluid/particles/id", std::span<const std::int64_t>(p.id));
  file.write_distributed_2d("/fluid/particles/position", flatten(p.position), 3);
  file.write_distributed_2d("/fluid/particles/velocity", flatten(p.velocity), 3);
  file.write_distributed_1d("/fluid/particles/mass", std::span<const double>(p.mass));
  file.write_distributed_1d("/fluid/particles/pressure", std::span<const double>(p.pressure));
  const std::vector<std::int64_t> rows{static_cast<std::int64_t>(p.size())};
  file.write_distributed_1d("/fluid/rank_rows", std::span<const std::int64_t>(rows));
  int rank = 0;
  MPI_Comm_rank(solver.comm(), &rank);
  const std::vector<double> cuts = rank == 0 ? solver.decomposition_cuts() : std::vector<double>{};
  file.write_distributed_1d("/fluid/decomposition_cuts", std::span<const double>(cuts));
  file.write_attribute("/fluid", "steps", static_cast<std::int64_t>(solver.steps()));
  file.write_attribute("/fluid", "removed_count", static_cast<std::int64_t>(solver.removed_count()));
  file.write_attribute("/fluid", "removed_volume", solver.removed_volume());
  file.write_attribute("/fluid", "run_state", run_state.dump());
}

FluidRestart read_fluid_state(MPI_Comm comm, const RestartPoint& point) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const Hdf5File file(comm, point.path, FileMode::read);
  if (!file.exists("/fluid/particles/id"))
    throw std::runtime_error(point.path.string() + " holds no fluid state");
  const std::int64_t total = file.shape("/fluid/particles/id").rows;
  std::int64_t first = 0, count = 0;
  FluidRestart restart;
  if (point.ranks == size) {
    // Each rank its own rows: the state as it was.
    const auto rows = file.read_rows_int64("/fluid/rank_rows", 0, size);
    for (int r = 0; r < rank; ++r) first += rows[static_cast<std::size_t>(r)];
    count = rows[static_cast<std::size_t>(rank)];
    restart.cuts = file.read_rows_double("/fluid/decomposition_cuts", 0, file.shape("/fluid/decomposition_cuts").rows);
  } else {
    first = total * rank / size;
    count = total * (rank + 1) / size - first;
  }
  Particles& p = restart.state.particles;
  p.id = file.read_rows_int64("/fluid/particles/id", first, count);
  p.position = vectors_of(file.read_rows_double("/fluid/particles/position", first, count));
  p.velocity = vectors_of(file.read_rows_double("/fluid/particles/velocity", first, count));
  p.mass = file.read_rows_double("/fluid/particles/mass", first, count);
  p.pressure = file.read_rows_double("/fluid/particles/pressure", first, count);
  restart.state.steps = file.read_int64_attribute("/fluid", "steps");
  restart.state.removed_count = file.read_int64_attribute("/fluid", "removed_count");
  restart.state.removed_volume = file.read_double_attribute("/fluid", "removed_volume");
  restart.run_state = nlohmann::json::parse(file.read_string_attribute("/fluid", "run_state"));
  return restart;
}

}  // namespace tankfsi::sph
