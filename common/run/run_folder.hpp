#pragma once
// RunFolder: the one folder a run writes into.
//
// Policy (documented in README): a folder is never half-overwritten. Each
// program claims the folder for its role before writing anything; a second run
// of the same program into the same folder is refused with exit status 2. The
// two partner programs of a coupled job share one folder, each under its own
// claim. Whole files are written to a temporary name and renamed, so a reader
// (or a killed run) never sees a half-written file; JSON documents shared by
// the partners (summary.json, provenance.json) are merged under a file lock.
#include <mpi.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace tankfsi {

class RunFolder {
 public:
  /// Collective over `comm`: rank 0 creates `folder` (and probes/) and claims it
  /// for `program`; on refusal every rank throws std::runtime_error with the
  /// reason, which the caller turns into an error at output.dir.
  static RunFolder claim(MPI_Comm comm, const std::filesystem::path& folder, const std::string& program);

  /// Collective: the folder of an earlier run of `program` that a restart
  /// continues (it must hold that program's claim); throws like claim().
  static RunFolder reopen(MPI_Comm comm, const std::filesystem::path& folder, const std::string& program);

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path probes() const { return path_ / "probes"; }
  [[nodiscard]] const std::string& program() const { return program_; }

  /// Writes `content` to folder/name through a temporary file and a rename.
  void write_file(const std::string& name, const std::string& content) const;
  /// Deep-merges `part` into the JSON document folder/name under an exclusive
  /// lock: objects merge key by key, anything else is replaced.
  void merge_json(const std::string& name, const nlohmann::json& part) const;

 private:
  RunFolder(std::filesystem::path path, std::string program) : path_(std::move(path)), program_(std::move(program)) {}
  std::filesystem::path path_;
  std::string program_;
};

/// Writes `content` to `path` through a temporary file in the same folder and an
/// atomic rename; throws std::runtime_error naming the file on failure.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

}  // namespace tankfsi
