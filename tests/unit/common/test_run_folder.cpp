// RunFolder, Logger and StageTimers: the run-folder rules on 1 and 2 ranks.
#include <catch2/catch.hpp>
#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "common/log/logger.hpp"
#include "common/log/stage_timers.hpp"
#include "common/run/run_folder.hpp"
#include "support/scratch_folder.hpp"

using namespace tankfsi;
namespace fs = std::filesystem;

namespace {

using testing::ScratchFolder;
constexpr auto shared = ScratchFolder::Scope::shared;

int world_rank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("a folder is claimed once per program and shared by partners", "[run_folder]") {
  const ScratchFolder scratch(shared);
  const auto folder = scratch.file("run");
  const auto fluid = RunFolder::claim(MPI_COMM_WORLD, folder, "sph_solver");
  CHECK(fs::is_directory(fluid.probes()));
  const auto structure = RunFolder::claim(MPI_COMM_WORLD, folder, "fem_solver");  // the partner joins
  CHECK(structure.path() == folder);
  CHECK_THROWS_WITH(RunFolder::claim(MPI_COMM_WORLD, folder, "sph_solver"),
                    "run folder '" + folder.string() +
                        "' already holds a run of sph_solver; choose another folder (--output DIR) or remove it");
}

TEST_CASE("a non-empty folder that is not a run folder is refused", "[run_folder]") {
  const ScratchFolder scratch(shared);
  const auto folder = scratch.file("run");
  if (world_rank() == 0) {
    fs::create_directories(folder);
    std::ofstream(folder / "thesis.tex") << "precious";
  }
  MPI_Barrier(MPI_COMM_WORLD);
  CHECK_THROWS_WITH(RunFolder::claim(MPI_COMM_WORLD, folder, "sph_solver"),
                    Catch::Contains("is not empty and is not a tankfsi run folder"));
  CHECK(read(folder / "thesis.tex") == "precious");
}

TEST_CASE("JSON documents merge the partners' parts key by key", "[run_folder]") {
  const ScratchFolder scratch(shared);
  const auto folder = scratch.file("run");
  const auto run = RunFolder::claim(MPI_COMM_WORLD, folder, "sph_solver");
  if (world_rank() == 0) {
    run.merge_json("summary.json", {{"programs", {{"sph_solver", {{"steps", 10}}}}}, {"sloshing_period_s", 5.9}});
    run.merge_json("summary.json", {{"programs", {{"fem_solver", {{"steps", 100}}}}}, {"bulging_period_s", 0.2}});
    const auto merged = nlohmann::json::parse(read(folder / "summary.json"));
    CHECK(merged["programs"]["sph_solver"]["steps"] == 10);
    CHECK(merged["programs"]["fem_solver"]["steps"] == 100);
    CHECK(merged["sloshing_period_s"] == 5.9);
    CHECK(merged["bulging_period_s"] == 0.2);
    // No temporary file is left behind by the atomic writes.
    for (const auto& entry : fs::directory_iterator(folder))
      CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
  }
}

TEST_CASE("the log file gets one line per info message and one error line per rank", "[log]") {
  const ScratchFolder scratch(shared);
  const auto& folder = scratch.path();
  const int rank = world_rank();
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  {
    Logger log(MPI_COMM_WORLD, "test_program", LogLevel::info);
    log.attach_file(folder / "run.log");
    log.info("pressure solved in ", 12, " iterations");
    log.debug("not written at level info");
    log.error("diverged on this rank");
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (rank == 0) {
    const auto text = read(folder / "run.log");
    auto count = [&](const std::string& s) {
      std::size_t n = 0;
      for (auto at = text.find(s); at != std::string::npos; at = text.find(s, at + 1)) ++n;
      return n;
    };
    CHECK(count("info: pressure solved in 12 iterations") == 1);
    CHECK(count("not written") == 0);
    CHECK(count("diverged on this rank") == static_cast<std::size_t>(size));
    CHECK(count("[test_program") == static_cast<std::size_t>(size) + 1);
  }
}

TEST_CASE("stage timers accumulate time and calls, nested stages included", "[timers]") {
  StageTimers timers;
  for (int i = 0; i < 2; ++i) {
    auto outer = timers.time("outer");
    auto inner = timers.time("inner");
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  CHECK(timers.calls("outer") == 2);
  CHECK(timers.calls("inner") == 2);
  CHECK(timers.seconds("inner") >= 0.020);  // two sleeps of 10 ms at least
  CHECK(timers.seconds("outer") >= timers.seconds("inner"));
  CHECK(timers.calls("never") == 0);
  const auto json = timers.to_json();
  CHECK(json.contains("outer"));
  CHECK(json["inner"]["calls"] == 2);
}
