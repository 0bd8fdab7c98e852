#include "common/run/checkpoint_series.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <regex>
#include <set>
#include <stdexcept>
#include <system_error>

#include "common/config/config_error.hpp"
#include "common/parallel/collective.hpp"
#include "common/run/provenance.hpp"
#include "common/run/stop_signal.hpp"

namespace fs = std::filesystem;

namespace tankfsi {
namespace {

const Origin restart_origin{"--restart", 0};

std::string checkpoint_name(const std::string& program, int number) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%06d", number);
  return program + "_" + digits + ".h5";
}

/// The numbers of `program`'s complete checkpoints in `folder`, ascending.
std::vector<int> checkpoint_numbers(const fs::path& folder, const std::string& program) {
  std::vector<int> numbers;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return numbers;
  const std::regex pattern(program + "_([0-9]{6})\\.h5");
  for (const auto& entry : fs::directory_iterator(folder, ec)) {
    std::smatch match;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, match, pattern)) numbers.push_back(std::stoi(match[1].str()));
  }
  std::sort(numbers.begin(), numbers.end());
  return numbers;
}

int rank_of(MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank;
}

}  // namespace

CheckpointSeries::CheckpointSeries(MPI_Comm comm, fs::path run_folder, std::string program, int first)
    : comm_(comm), folder_(std::move(run_folder) / "checkpoints"), program_(std::move(program)), first_(first),
      next_(first) {}

fs::path CheckpointSeries::path(int number) const { return folder_ / checkpoint_name(program_, number); }

std::unique_ptr<Hdf5File> CheckpointSeries::begin(double time, const CaseConfig& config) {
  std::string problem;
  if (rank_of(comm_) == 0) {
    std::error_code ec;
    fs::create_directories(folder_, ec);
    if (ec) problem = "cannot create " + folder_.string() + ": " + ec.message();
  }
  throw_if_any_rank_failed(comm_, "checkpoint", problem);
  int ranks = 1;
  MPI_Comm_size(comm_, &ranks);
  auto file = std::make_unique<Hdf5File>(comm_, path(next_).string() + ".partial", FileMode::truncate);
  file->write_attribute("/", "program", program_);
  file->write_attribute("/", "number", static_cast<std::int64_t>(next_));
  file->write_attribute("/", "time_s", time);
  file->write_attribute("/", "ranks", static_cast<std::int64_t>(ranks));
  file->write_attribute("/", "case_yaml", config.resolved_yaml());
  file->write_attribute("/", "tankfsi_version", tankfsi_version() + " (" + tankfsi_git_commit() + ")");
  return file;
}

fs::path CheckpointSeries::commit(std::unique_ptr<Hdf5File> file) {
  const fs::path partial = file->path();
  file->flush();
  file.reset();  // closed on every rank before the rename
  MPI_Barrier(comm_);
  const fs::path final_path = path(next_);
  std::string problem;
  if (rank_of(comm_) == 0) {
    std::error_code ec;
    fs::rename(partial, final_path, ec);
    if (ec) problem = "cannot rename " + partial.string() + ": " + ec.message();
    for (const int old : checkpoint_numbers(folder_, program_))
      if (old < next_ - 1) fs::remove(path(old), ec);  // a failed removal only leaves a file
  }
  throw_if_any_rank_failed(comm_, "checkpoint", problem);
  ++next_;
  return final_path;
}

CheckpointDecision checkpoint_after_step(MPI_Comm comm, double t, double interval, double& next_time) {
  CheckpointDecision decision;
  decision.stop_signal = agreed_stop_signal(comm);
  decision.due = t >= next_time * (1.0 - 1e-12);
  if (decision.due) next_time = next_output_time(t, interval);
  decision.due = decision.due || decision.stop_signal != 0;
  return decision;
}

std::string last_good_checkpoint(const std::function<std::filesystem::path()>& write) {
  try {
    return " and checkpoint " + write().string();
  } catch (const std::runtime_error& failure) {
    return " (no checkpoint: " + std::string(failure.what()) + ")";
  }
}

double next_output_time(double t, double interval) {
  if (!(interval > 0.0)) return std::numeric_limits<double>::infinity();
  return interval * (std::floor(t / interval * (1.0 + 1e-12)) + 1.0);
}

std::vector<std::string> restart_case_differences(const std::string& written_yaml, const std::string& current_yaml) {
  YAML::Node written = YAML::Load(written_yaml);
  YAML::Node current = YAML::Load(current_yaml);
  // How the linear systems are solved, when a run counts as diverging and how
  // long a partner is awaited do not change the state: a restart may change
  // them (after a failed PPE, say).
  for (YAML::Node* node : {&written, &current}) {
    if ((*node)["fluid"] && (*node)["fluid"]["time_step"]) (*node)["fluid"]["time_step"].remove("breach_courant");
    if ((*node)["fluid"] && (*node)["fluid"]["ppe"]) {
      (*node)["fluid"]["ppe"].remove("solver_options");
      if ((*node)["fluid"]["ppe"].size() == 0) (*node)["fluid"].remove("ppe");
    }
    if ((*node)["structure"]) (*node)["structure"].remove("solver_options");
    if ((*node)["coupling"]) (*node)["coupling"].remove("timeout");
  }
  std::set<std::string> keys;
  for (const auto& node : {written, current})
    for (const auto& entry : node) keys.insert(entry.first.as<std::string>());
  std::vector<std::string> differences;
  for (const auto& key : keys) {
    if (key == "title" || key == "output" || key == "end_time") continue;
    YAML::Emitter a, b;
    a << written[key];
    b << current[key];
    if (std::string(a.c_str()) != std::string(b.c_str())) differences.push_back(key);
  }
  return differences;
}

RestartPoint find_restart_point(MPI_Comm comm, const fs::path& run_folder, const std::string& program,
                                const std::string& spec, const CaseConfig& config) {
  // Rank 0 looks at the folder; every rank opens the file it found.
  std::string found;
  std::string problem;
  if (rank_of(comm) == 0) {
    const fs::path folder = run_folder / "checkpoints";
    std::error_code ec;
    if (spec.empty() || spec == "latest") {
      // Every program that ran here must have it: the partners continue together.
      std::vector<std::string> programs;
      for (const auto& entry : fs::directory_iterator(run_folder / ".claims", ec))
        if (entry.is_regular_file(ec) && entry.path().extension().empty()) programs.push_back(entry.path().filename());
      if (std::find(programs.begin(), programs.end(), program) == programs.end()) programs.push_back(program);
      std::vector<int> common = checkpoint_numbers(folder, program);
      for (const auto& other : programs) {
        const auto theirs = checkpoint_numbers(folder, other);
        std::erase_if(common, [&](int k) { return !std::binary_search(theirs.begin(), theirs.end(), k); });
      }
      if (common.empty())
        problem = "no checkpoint in " + folder.string() + " that every program of the run (" +
                  [&] { std::string s; for (const auto& p : programs) s += (s.empty() ? "" : ", ") + p; return s; }() +
                  ") has";
      else
        found = (folder / checkpoint_name(program, common.back())).string();
    } else if (std::all_of(spec.begin(), spec.end(), [](char c) { return c >= '0' && c <= '9'; }) && spec.size() < 9) {
      found = (folder / checkpoint_name(program, std::stoi(spec))).string();
      if (!fs::is_regular_file(found, ec)) problem = "no checkpoint " + found;
    } else {
      found = spec;
      if (!fs::is_regular_file(found, ec)) problem = "no checkpoint file '" + spec + "'";
    }
  }
  problem = broadcast_text(comm, problem);
  if (!problem.empty()) throw ConfigError(restart_origin, "", problem);
  RestartPoint point;
  point.path = broadcast_text(comm, found);
  try {
    const Hdf5File file(comm, point.path, FileMode::read);
    const std::string writer = file.read_string_attribute("/", "program");
    if (writer != program)
      throw ConfigError(restart_origin, "", point.path.string() + " is a checkpoint of " + writer + ", not " + program);
    point.number = static_cast<int>(file.read_int64_attribute("/", "number"));
    point.time = file.read_double_attribute("/", "time_s");
    point.ranks = static_cast<int>(file.read_int64_attribute("/", "ranks"));
    const auto differences = restart_case_differences(file.read_string_attribute("/", "case_yaml"), config.resolved_yaml());
    if (!differences.empty()) {
      std::string keys;
      for (const auto& k : differences) keys += (keys.empty() ? "" : ", ") + k;
      throw ConfigError(restart_origin, "", point.path.string() + " was written for another case: it differs in " +
                                                keys + " (a restart may change only title, output, end_time and solver options)");
    }
  } catch (const ConfigError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw ConfigError(restart_origin, "", std::string("cannot read checkpoint: ") + e.what());
  }
  return point;
}

}  // namespace tankfsi
