#include "coupling/restart/restart_state_file.hpp"

#include <stdexcept>

namespace tankfsi::coupling {
namespace {

constexpr std::size_t report_columns = 13;

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

}  // namespace

void write_restart_state(Hdf5File& file, const std::string& group, const CouplingRestartState& state, bool replicated) {
  const bool writer = rank_of(file.comm()) == 0;
  for (const auto& [name, values] : state.arrays) {
    const std::span<const double> mine = replicated && !writer ? std::span<const double>() : std::span<const double>(values);
    file.write_distributed_1d(group + "/arrays/" + name, mine);
    const std::vector<std::int64_t> rows{static_cast<std::int64_t>(mine.size())};
    file.write_distributed_1d(group + "/rows/" + name, std::span<const std::int64_t>(rows));
  }
  std::vector<double> reports;
  if (writer)
    for (const WindowReport& r : state.reports) {
      reports.insert(reports.end(), {static_cast<double>(r.window), r.start_time, r.end_time,
                                     static_cast<double>(r.iterations), r.converged ? 1.0 : 0.0,
                                     r.displacement_residual, r.force_residual});
      reports.insert(reports.end(), r.impulse_given.begin(), r.impulse_given.end());
      reports.insert(reports.end(), r.impulse_applied.begin(), r.impulse_applied.end());
    }
  file.write_distributed_2d(group + "/reports", reports, report_columns);
  const std::vector<double> numbers = writer ? state.history_numbers : std::vector<double>{};
  file.write_distributed_1d(group + "/history_numbers", std::span<const double>(numbers));
  file.write_attribute(group, "window", static_cast<std::int64_t>(state.window));
  file.write_attribute(group, "window_start_s", state.window_start);
}

CouplingRestartState read_restart_state(const Hdf5File& file, const std::string& group, bool replicated) {
  if (!file.exists(group + "/reports"))
    throw std::runtime_error(file.path().string() + " holds no coupling state (" + group + ")");
  const int rank = rank_of(file.comm());
  int size = 1;
  MPI_Comm_size(file.comm(), &size);
  CouplingRestartState state;
  state.window = static_cast<int>(file.read_int64_attribute(group, "window"));
  state.window_start = file.read_double_attribute(group, "window_start_s");
  for (const auto& name : file.group_members(group + "/arrays")) {
    const std::string dataset = group + "/arrays/" + name;
    if (replicated) {
      state.arrays[name] = file.read_rows_double(dataset, 0, file.shape(dataset).rows);
      continue;
    }
    const std::string rows_name = group + "/rows/" + name;
    if (file.shape(rows_name).rows != size)
      throw std::runtime_error(file.path().string() + ": the coupling state was written on " +
                               std::to_string(file.shape(rows_name).rows) + " ranks, not " + std::to_string(size));
    const auto rows = file.read_rows_int64(rows_name, 0, size);
    std::int64_t first = 0;
    for (int r = 0; r < rank; ++r) first += rows[static_cast<std::size_t>(r)];
    state.arrays[name] = file.read_rows_double(dataset, first, rows[static_cast<std::size_t>(rank)]);
  }
  const auto reports = file.read_rows_double(group + "/reports", 0, file.shape(group + "/reports").rows);
  for (std::size_t i = 0; i + report_columns <= reports.size(); i += report_columns) {
    WindowReport r;
    r.window = static_cast<int>(reports[i]);
    r.start_time = reports[i + 1];
    r.end_time = reports[i + 2];
    r.iterations = static_cast<int>(reports[i + 3]);
    r.converged = reports[i + 4] != 0.0;
    r.displacement_residual = reports[i + 5];
    r.force_residual = reports[i + 6];
    for (std::size_t k = 0; k < 3; ++k) {
      r.impulse_given[k] = reports[i + 7 + k];
      r.impulse_applied[k] = reports[i + 10 + k];
    }
    state.reports.push_back(r);
  }
  state.history_numbers =
      file.read_rows_double(group + "/history_numbers", 0, file.shape(group + "/history_numbers").rows);
  return state;
}

}  // namespace tankfsi::coupling
