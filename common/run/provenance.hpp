#pragma once
// Provenance: what produced a run, recorded in provenance.json so that any
// figure can be traced to a version, a commit, a command line and a machine.
#include <mpi.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tankfsi {

std::string tankfsi_version();     ///< "0.1.0"
std::string tankfsi_git_commit();  ///< commit hash, "-modified" when the tree had changes
std::string utc_timestamp();       ///< ISO 8601, e.g. 2026-11-22T03:14:39Z

/// This program's entry of provenance.json (collective over comm: gathers hosts).
nlohmann::json program_provenance(MPI_Comm comm, const std::string& program, const std::vector<std::string>& arguments,
                                  const std::string& case_file);

}  // namespace tankfsi
