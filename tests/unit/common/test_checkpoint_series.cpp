// Checkpoints: row reads of Hdf5File, the series' naming, renaming and
// rotation, what --restart finds (a checkpoint cut short by a kill is never
// taken), and the outputs that a restart continues (probe rows and series
// snapshots after the checkpoint's time are dropped).
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <semaphore.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "common/config/case_schema.hpp"
#include "common/config/config_error.hpp"
#include "common/io/field_series_writer.hpp"
#include "common/io/probe_file.hpp"
#include "common/run/checkpoint_series.hpp"
#include "common/parallel/collective.hpp"
#include "common/run/stop_signal.hpp"
#include "support/mpi_world.hpp"
#include "support/scratch_folder.hpp"

using namespace tankfsi;
namespace fs = std::filesystem;

namespace {

using testing::world_rank;
using testing::world_size;

CaseConfig case_with(const fs::path& folder, const std::string& extra) {
  const fs::path file = folder / ("case" + std::to_string(std::hash<std::string>{}(extra)) + ".yaml");
  if (world_rank() == 0) {
    std::ofstream out(file);
    out << "title: restart test\nend_time: 1.0\nfluid:\n  dimension: 2\n  density: 1000\n  viscosity: 0.001\n  spacing: 0.02\n"
        << extra;
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return CaseConfig::load(file, {}, case_schema());
}

void write_checkpoint(CheckpointSeries& series, double time, const CaseConfig& config) {
  auto file = series.begin(time, config);
  const std::vector<double> values(static_cast<std::size_t>(world_rank() + 1), time);
  file->write_distributed_1d("/state/values", std::span<const double>(values));
  series.commit(std::move(file));
}

}  // namespace

TEST_CASE("Hdf5File reads back any slice of rows and numeric attributes", "[checkpoint]") {
  const testing::ScratchFolder folder(testing::ScratchFolder::Scope::shared);
  const fs::path path = folder.path() / "rows.h5";
  const int rank = world_rank();
  const int size = world_size();
  {
    Hdf5File file(MPI_COMM_WORLD, path, FileMode::truncate);
    // Rank r writes r + 1 rows (r, 10 r + k) for k = 0..r.
    std::vector<double> rows;
    for (int k = 0; k <= rank; ++k) rows.insert(rows.end(), {double(rank), 10.0 * rank + k});
    file.write_distributed_2d("/a/rows", rows, 2);
    file.write_distributed_1d("/a/empty", std::span<const double>());
    file.write_attribute("/a", "count", std::int64_t{42});
    file.write_attribute("/a", "time", 0.1 + 0.2);
  }
  const Hdf5File file(MPI_COMM_WORLD, path, FileMode::read);
  const std::int64_t total = std::int64_t(size) * (size + 1) / 2;
  CHECK(file.shape("/a/rows").rows == total);
  CHECK(file.shape("/a/rows").columns == 2);
  CHECK(file.exists("/a/rows"));
  CHECK_FALSE(file.exists("/a/missing/rows"));
  CHECK(file.read_int64_attribute("/a", "count") == 42);
  CHECK(file.read_double_attribute("/a", "time") == 0.1 + 0.2);
  CHECK(file.read_double_attribute("/a", "count") == 42.0);
  // Every rank reads the last rank's block, whatever it wrote itself.
  const std::int64_t first = total - size;
  const auto last = file.read_rows_double("/a/rows", first, size);
  REQUIRE(last.size() == 2 * static_cast<std::size_t>(size));
  for (int k = 0; k < size; ++k) {
    CHECK(last[2 * static_cast<std::size_t>(k)] == size - 1);
    CHECK(last[2 * static_cast<std::size_t>(k) + 1] == 10.0 * (size - 1) + k);
  }
  CHECK(file.read_rows_double("/a/rows", 0, 0).empty());
  CHECK(file.shape("/a/empty").rows == 0);
  CHECK(file.read_rows_double("/a/empty", 0, 0).empty());  // no storage behind it
  CHECK_THROWS_AS(file.read_rows_double("/a/rows", total - 1, 2), std::invalid_argument);
}

// A job killed inside MPI_File_open or while a file is open leaves Open MPI's
// "sm" shared-file-pointer semaphore for that file name taken; a later job
// opening a file of the same name then hung (the restart tests' checkpoint 2
// did). MpiSession keeps MPI-IO off shared file pointers: with such a
// semaphore left behind the file opens and is written. Without it this test
// never returns (ctest's timeout fails it).
TEST_CASE("a file opens though a killed job left its name's shared-pointer semaphore taken", "[checkpoint]") {
  const testing::ScratchFolder folder(testing::ScratchFolder::Scope::shared);
  const std::string name = broadcast_text(MPI_COMM_WORLD, "left_by_a_killed_job_" + std::to_string(getpid()) + ".h5");
  const std::string semaphore = "OMPIO_" + name;  // ompio's name for it: "OMPIO_" + base name
  if (world_rank() == 0) {
    sem_t* taken = sem_open(semaphore.c_str(), O_CREAT | O_EXCL, 0644, 0);  // value 0: held by nobody alive
    REQUIRE(taken != SEM_FAILED);
    sem_close(taken);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  {
    Hdf5File file(MPI_COMM_WORLD, folder.path() / name, FileMode::truncate);
    file.create_group("/run");
    file.write_attribute("/run", "written", std::int64_t{1});
  }
  if (world_rank() == 0) sem_unlink(semaphore.c_str());
  Hdf5File file(MPI_COMM_WORLD, folder.path() / name, FileMode::read);
  CHECK(file.read_int64_attribute("/run", "written") == 1);
}

TEST_CASE("checkpoints are renamed into place, the last two kept, and a cut-short one never taken", "[checkpoint]") {
  const testing::ScratchFolder folder(testing::ScratchFolder::Scope::shared);
  const fs::path run = folder.path() / "run";
  if (world_rank() == 0) fs::create_directories(run / ".claims"), std::ofstream(run / ".claims" / "prog");
  MPI_Barrier(MPI_COMM_WORLD);
  const CaseConfig config = case_with(folder.path(), "");
  CheckpointSeries series(MPI_COMM_WORLD, run, "prog");
  for (int k = 1; k <= 3; ++k) write_checkpoint(series, 0.25 * k, config);
  CHECK(series.written() == 3);
  CHECK_FALSE(fs::exists(series.path(1)));
  CHECK(fs::exists(series.path(2)));
  CHECK(fs::exists(series.path(3)));
  // A fourth, cut short as by a kill while writing: begun, never committed.
  { auto unfinished = series.begin(1.0, config); }
  CHECK(fs::exists(series.path(4).string() + ".partial"));
  CHECK_FALSE(fs::exists(series.path(4)));

  const RestartPoint latest = find_restart_point(MPI_COMM_WORLD, run, "prog", "latest", config);
  CHECK(latest.number == 3);
  CHECK(latest.time == 0.75);
  CHECK(latest.ranks == world_size());
  CHECK(latest.path == series.path(3));
  CHECK(find_restart_point(MPI_COMM_WORLD, run, "prog", "2", config).time == 0.5);
  CHECK(find_restart_point(MPI_COMM_WORLD, run, "prog", series.path(2).string(), config).number == 2);
  CHECK_THROWS_WITH(find_restart_point(MPI_COMM_WORLD, run, "prog", "1", config),
                    Catch::Contains("--restart") && Catch::Contains("no checkpoint") && Catch::Contains("prog_000001.h5"));
  CHECK_THROWS_WITH(find_restart_point(MPI_COMM_WORLD, run, "other", series.path(3).string(), config),
                    Catch::Contains("is a checkpoint of prog, not other"));

  // The case may change in its end time and outputs only.
  const CaseConfig longer = case_with(folder.path(), "output:\n  field_interval: 0.5\n");
  CHECK(find_restart_point(MPI_COMM_WORLD, run, "prog", "latest", longer).number == 3);
  const CaseConfig other = case_with(folder.path(), "  kernel: wendland_c2\n");
  CHECK_THROWS_WITH(find_restart_point(MPI_COMM_WORLD, run, "prog", "latest", other),
                    Catch::Contains("written for another case") && Catch::Contains("differs in fluid"));
}

TEST_CASE("latest is the newest checkpoint every program of the run has", "[checkpoint]") {
  const testing::ScratchFolder folder(testing::ScratchFolder::Scope::shared);
  const fs::path run = folder.path() / "run";
  if (world_rank() == 0) {
    fs::create_directories(run / ".claims");
    std::ofstream(run / ".claims" / "fluid_program");
    std::ofstream(run / ".claims" / "structure_program");
    std::ofstream(run / ".claims" / "summary.json.lock");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const CaseConfig config = case_with(folder.path(), "");
  CheckpointSeries fluid(MPI_COMM_WORLD, run, "fluid_program");
  CheckpointSeries structure(MPI_COMM_WORLD, run, "structure_program");
  for (int k = 1; k <= 3; ++k) write_checkpoint(fluid, 0.1 * k, config);
  for (int k = 1; k <= 2; ++k) write_checkpoint(structure, 0.1 * k, config);  // killed before its third
  CHECK(find_restart_point(MPI_COMM_WORLD, run, "fluid_program", "latest", config).number == 2);
  CHECK(find_restart_point(MPI_COMM_WORLD, run, "structure_program", "latest", config).number == 2);
  if (world_rank() == 0) fs::remove(structure.path(2)), fs::remove(structure.path(1));
  MPI_Barrier(MPI_COMM_WORLD);
  CHECK_THROWS_WITH(find_restart_point(MPI_COMM_WORLD, run, "fluid_program", "latest", config),
                    Catch::Contains("that every program of the run (") && Catch::Contains("structure_program"));
}

TEST_CASE("case differences name the sections, leaving out title, output and end time", "[checkpoint]") {
  const std::string a = "title: a\nend_time: 1\noutput:\n  dir: x\nfluid:\n  spacing: 0.02\nstructure:\n  k: 1\n";
  const std::string b = "title: b\nend_time: 2\noutput:\n  dir: y\nfluid:\n  spacing: 0.01\nstructure:\n  k: 1\n";
  CHECK(restart_case_differences(a, a).empty());
  CHECK(restart_case_differences(a, b) == std::vector<std::string>{"fluid"});
  CHECK(restart_case_differences(a, "fluid:\n  spacing: 0.02\n") == std::vector<std::string>{"structure"});
  const std::string solved = "fluid:\n  spacing: 0.02\n  ppe:\n    solver_options: -ppe_ksp_rtol 1e-12\nstructure:\n  k: 1\n"
                             "  solver_options: -shell_pc_type lu\n";
  CHECK(restart_case_differences(a, solved).empty());
}

TEST_CASE("a probe file continued at a restart keeps its rows up to the restart time", "[checkpoint]") {
  const testing::ScratchFolder folder;
  const auto path = folder.file("probe.csv");
  {
    ProbeFile probe(path, {"h_m"}, 1.0);
    for (const double t : {0.0, 0.1, 0.1 + 0.2, 0.4, 0.5}) {
      const double value[] = {2 * t};
      probe.append(t, value);
    }
  }
  {
    ProbeFile probe(path, {"h_m"}, 1.0, 0.1 + 0.2);  // 0.30000000000000004: the row of that very time stays
    const double value[] = {-1.0};
    probe.append(0.45, value);
    CHECK_THROWS_AS(probe.append(0.2, value), std::invalid_argument);  // before the restart time
  }
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  REQUIRE(lines.size() == 5);
  CHECK(lines[0] == "time_s,h_m");
  CHECK(lines[3].starts_with("0.30000000000000004,"));
  CHECK(lines[4] == "0.45,-1");
  CHECK_THROWS_WITH(ProbeFile(path, {"other_m"}, 1.0, 0.1), Catch::Contains("its header is 'time_s,h_m'"));
  CHECK_THROWS_WITH(ProbeFile(folder.file("missing.csv"), {"h_m"}, 1.0, 0.1), Catch::Contains("missing or empty"));
}

TEST_CASE("a series continued at a restart drops the snapshots after the restart time", "[checkpoint]") {
  const testing::ScratchFolder folder(testing::ScratchFolder::Scope::shared);
  const std::vector<std::int64_t> ids{world_rank()};
  const std::vector<double> position{1.0, 2.0, 3.0};
  const auto write = [&](FieldSeriesWriter& series, double t) {
    series.write_particles(t, ParticleSnapshot{ids, position, {}});
  };
  {
    FieldSeriesWriter series(MPI_COMM_WORLD, folder.path(), "p");
    for (const double t : {0.0, 0.1, 0.2, 0.3}) write(series, t);
  }
  {
    FieldSeriesWriter series(MPI_COMM_WORLD, folder.path(), "p", FileMode::append, 0.1);
    CHECK(series.snapshot_count() == 2);
    write(series, 0.15);
  }
  const Hdf5File file(MPI_COMM_WORLD, folder.path() / "p.h5", FileMode::read);
  const auto groups = file.group_members("/");
  CHECK(groups == std::vector<std::string>{"step_0000000", "step_0000001", "step_0000002"});
  CHECK(file.read_double_attribute("/step_0000002", "time") == 0.15);
  std::ifstream xdmf(folder.path() / "p.xdmf");
  const std::string text((std::istreambuf_iterator<char>(xdmf)), std::istreambuf_iterator<char>());
  CHECK(text.find("<Time Value=\"0.2\"") == std::string::npos);
  CHECK(text.find("<Time Value=\"0.15\"") != std::string::npos);
}

TEST_CASE("a stop signal is agreed over the ranks", "[checkpoint]") {
  CHECK(agreed_stop_signal(MPI_COMM_WORLD) == 0);
  if (world_rank() == world_size() - 1) simulate_stop_signal(SIGUSR1);
  CHECK(agreed_stop_signal(MPI_COMM_WORLD) == SIGUSR1);
  CHECK(std::string(stop_signal_name(SIGUSR1)) == "SIGUSR1");
  simulate_stop_signal(0);
  CHECK(agreed_stop_signal(MPI_COMM_WORLD) == 0);
}
