#include "common/run/run_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/parallel/collective.hpp"

namespace tankfsi {

namespace fs = std::filesystem;

namespace {

std::string system_error_text() { return std::strerror(errno); }

// Exclusive creation is the claim: of two runs racing for one folder, one wins.
std::string try_claim(const fs::path& folder, const std::string& program) {
  const std::string name = folder.string();
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec)) return "'" + name + "' exists and is not a folder";
  // A folder holding anything but a partner's run is someone else's: never write into it.
  if (fs::is_directory(folder, ec) && !fs::is_empty(folder, ec) && !fs::is_directory(folder / ".claims", ec))
    return "'" + name + "' exists, is not empty and is not a tankfsi run folder; choose another (--output DIR)";
  fs::create_directories(folder / ".claims", ec);
  if (!ec) fs::create_directories(folder / "probes", ec);
  if (ec) return "cannot create run folder '" + name + "': " + ec.message();
  const fs::path claim = folder / ".claims" / program;
  const int fd = ::open(claim.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      return "run folder '" + name + "' already holds a run of " + program +
             "; choose another folder (--output DIR) or remove it";
    return "cannot claim run folder '" + name + "': " + system_error_text();
  }
  ::close(fd);
  return "";
}

void deep_merge(nlohmann::json& into, const nlohmann::json& part) {
  if (!into.is_object() || !part.is_object()) {
    into = part;
    return;
  }
  for (auto it = part.begin(); it != part.end(); ++it) deep_merge(into[it.key()], it.value());
}

}  // namespace

RunFolder RunFolder::claim(MPI_Comm comm, const fs::path& folder, const std::string& program) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string refusal = broadcast_text(comm, rank == 0 ? try_claim(folder, program) : "");
  if (!refusal.empty()) throw std::runtime_error(refusal);
  return RunFolder(folder, program);
}

RunFolder RunFolder::reopen(MPI_Comm comm, const fs::path& folder, const std::string& program) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string refusal;
  if (rank == 0) {
    std::error_code ec;
    if (!fs::exists(folder / ".claims" / program, ec))
      refusal = "run folder '" + folder.string() + "' holds no run of " + program + " to restart";
  }
  refusal = broadcast_text(comm, refusal);
  if (!refusal.empty()) throw std::runtime_error(refusal);
  return RunFolder(folder, program);
}

void write_file_atomically(const fs::path& path, const std::string& content) {
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("cannot write '" + temporary.string() + "': " + system_error_text());
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw std::runtime_error("cannot write '" + path.string() + "': " + ec.message());
  }
}

void RunFolder::write_file(const std::string& name, const std::string& content) const {
  write_file_atomically(path_ / name, content);
}

void RunFolder::merge_json(const std::string& name, const nlohmann::json& part) const {
  // The lock file is separate from the document, which is replaced by rename.
  const fs::path lock_path = path_ / ".claims" / (name + ".lock");
  const int lock = ::open(lock_path.c_str(), O_RDWR | O_CREAT, 0644);
  if (lock < 0) throw std::runtime_error("cannot open '" + lock_path.string() + "': " + system_error_text());
  ::flock(lock, LOCK_EX);
  try {
    nlohmann::json document = nlohmann::json::object();
    if (std::ifstream in(path_ / name); in) {
      try {
        document = nlohmann::json::parse(in);
      } catch (const nlohmann::json::exception&) {
        document = nlohmann::json::object();  // unreadable: rewritten whole below
      }
    }
    deep_merge(document, part);
    write_file(name, document.dump(2) + "\n");
  } catch (...) {
    ::flock(lock, LOCK_UN);
    ::close(lock);
    throw;
  }
  ::flock(lock, LOCK_UN);
  ::close(lock);
}

}  // namespace tankfsi
