#include "common/run/provenance.hpp"

#include <unistd.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <set>

namespace tankfsi {

std::string tankfsi_version() { return TANKFSI_VERSION; }
std::string tankfsi_git_commit() { return TANKFSI_GIT_COMMIT; }

std::string utc_timestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

nlohmann::json program_provenance(MPI_Comm comm, const std::string& program, const std::vector<std::string>& arguments,
                                  const std::string& case_file) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  std::vector<char> all(static_cast<std::size_t>(size) * MPI_MAX_PROCESSOR_NAME);
  MPI_Gather(name, MPI_MAX_PROCESSOR_NAME, MPI_CHAR, all.data(), MPI_MAX_PROCESSOR_NAME, MPI_CHAR, 0, comm);
  std::set<std::string> hosts;
  for (int r = 0; r < size; ++r) hosts.insert(std::string(&all[static_cast<std::size_t>(r) * MPI_MAX_PROCESSOR_NAME]));

  int world_size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  return {
      {"program", program},
      {"started", utc_timestamp()},
      {"command_line", arguments},
      {"case_file", std::filesystem::absolute(case_file).string()},
      {"working_directory", std::filesystem::current_path().string()},
      {"mpi_ranks", size},
      {"mpi_world_ranks", world_size},
      {"hosts", std::vector<std::string>(hosts.begin(), hosts.end())},
      {"process_id_rank0", static_cast<long>(::getpid())},
  };
}

}  // namespace tankfsi
