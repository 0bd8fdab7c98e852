#include "sph_solver/app/fluid_checkpoint.hpp"

#include <memory>
#include <stdexcept>
#include <string>

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

const char* const hierarchy_group = "/fluid/pressure_hierarchy";

std::string in_hierarchy(const char* name) { return std::string(hierarchy_group) + "/" + name; }

/// The kept hierarchy's basis (kept_hierarchy.hpp) and when the next is built.
void write_kept_hierarchy(Hdf5File& file, const PressurePoisson::KeptState& kept) {
  const KeptHierarchy::Basis& basis = kept.hierarchy->basis();
  std::vector<std::int64_t> lengths(basis.ids.size());
  for (std::size_t i = 0; i < lengths.size(); ++i) lengths[i] = basis.row_begin[i + 1] - basis.row_begin[i];
  file.write_distributed_1d(in_hierarchy("ids"), std::span<const std::int64_t>(basis.ids));
  file.write_distributed_1d(in_hierarchy("row_lengths"), std::span<const std::int64_t>(lengths));
  file.write_distributed_1d(in_hierarchy("columns"), std::span<const std::int64_t>(basis.columns));
  file.write_distributed_1d(in_hierarchy("values"), std::span<const double>(basis.values));
  const std::vector<std::int64_t> rows{static_cast<std::int64_t>(basis.ids.size())};
  const std::vector<std::int64_t> entries{static_cast<std::int64_t>(basis.columns.size())};
  file.write_distributed_1d(in_hierarchy("rank_rows"), std::span<const std::int64_t>(rows));
  file.write_distributed_1d(in_hierarchy("rank_entries"), std::span<const std::int64_t>(entries));
  file.write_attribute(hierarchy_group, "first_iterations", static_cast<std::int64_t>(kept.first_iterations));
  file.write_attribute(hierarchy_group, "rebuild", static_cast<std::int64_t>(kept.rebuild ? 1 : 0));
}

/// This rank's share of what write_kept_hierarchy() wrote on as many ranks:
/// the same hierarchy, built from the same rows.
PressurePoisson::KeptState read_kept_hierarchy(MPI_Comm comm, const Hdf5File& file) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const auto rows = file.read_rows_int64(in_hierarchy("rank_rows"), 0, size);
  const auto entries = file.read_rows_int64(in_hierarchy("rank_entries"), 0, size);
  std::int64_t first_row = 0, first_entry = 0;
  for (int r = 0; r < rank; ++r) {
    first_row += rows[static_cast<std::size_t>(r)];
    first_entry += entries[static_cast<std::size_t>(r)];
  }
  const std::int64_t row_count = rows[static_cast<std::size_t>(rank)];
  const std::int64_t entry_count = entries[static_cast<std::size_t>(rank)];
  KeptHierarchy::Basis basis;
  basis.ids = file.read_rows_int64(in_hierarchy("ids"), first_row, row_count);
  const auto lengths = file.read_rows_int64(in_hierarchy("row_lengths"), first_row, row_count);
  basis.row_begin.assign(1, 0);
  for (const std::int64_t length : lengths) basis.row_begin.push_back(basis.row_begin.back() + length);
  if (basis.row_begin.back() != entry_count)
    throw std::runtime_error(std::string(hierarchy_group) + ": the row lengths do not add up to the entries");
  basis.columns = file.read_rows_int64(in_hierarchy("columns"), first_entry, entry_count);
  basis.values = file.read_rows_double(in_hierarchy("values"), first_entry, entry_count);
  PressurePoisson::KeptState kept;
  kept.hierarchy = std::make_shared<KeptHierarchy>(comm, std::move(basis));
  kept.first_iterations = static_cast<int>(file.read_int64_attribute(hierarchy_group, "first_iterations"));
  kept.rebuild = file.read_int64_attribute(hierarchy_group, "rebuild") != 0;
  return kept;
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
  const PressurePoisson::KeptState kept = solver.kept_pressure_hierarchy();
  if (kept.hierarchy != nullptr) write_kept_hierarchy(file, kept);  // on every rank or none
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
  // The kept hierarchy goes on only with the rows it was built on (on
  // another rank count a new one is built at the first step).
  if (point.ranks == size && file.exists(in_hierarchy("ids")))
    restart.state.pressure_solver = read_kept_hierarchy(comm, file);
  return restart;
}

}  // namespace tankfsi::sph
