#include "common/parallel/program_groups.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace tankfsi {

namespace {

constexpr int role_length = 32;
constexpr int intercomm_tag = 7301;

struct RankIdentity {
  int appnum = -1;  ///< -1: the launcher did not set MPI_APPNUM
  std::array<char, role_length> role{};
};

int own_appnum(MPI_Comm world) {
  int* value = nullptr;
  int flag = 0;
  MPI_Comm_get_attr(world, MPI_APPNUM, &value, &flag);
  return flag && value ? *value : -1;
}

std::string role_of(const RankIdentity& identity) {
  return std::string(identity.role.data(), strnlen(identity.role.data(), role_length));
}

// The colour of every rank: its program's index in order of first appearance.
std::vector<int> program_colours(const std::vector<RankIdentity>& ranks, bool by_appnum) {
  std::vector<std::string> keys;
  std::vector<int> colours;
  for (const auto& r : ranks) {
    const std::string key = by_appnum ? std::to_string(r.appnum) : role_of(r);
    auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) it = keys.insert(keys.end(), key);
    colours.push_back(static_cast<int>(it - keys.begin()));
  }
  return colours;
}

// MPI_APPNUM separates the programs when every rank has one and no number is
// shared by two roles.
bool appnum_separates_roles(const std::vector<RankIdentity>& ranks) {
  for (const auto& r : ranks) {
    if (r.appnum < 0) return false;
    for (const auto& other : ranks)
      if (other.appnum == r.appnum && role_of(other) != role_of(r)) return false;
  }
  return true;
}

}  // namespace

ProgramGroups split_program_groups(MPI_Comm world, const std::string& role) {
  if (role.size() >= static_cast<std::size_t>(role_length))
    throw std::invalid_argument("program role '" + role + "' is too long");
  int world_rank = 0;
  int world_size = 1;
  MPI_Comm_rank(world, &world_rank);
  MPI_Comm_size(world, &world_size);

  RankIdentity mine;
  mine.appnum = own_appnum(world);
  std::copy(role.begin(), role.end(), mine.role.begin());
  std::vector<RankIdentity> ranks(static_cast<std::size_t>(world_size));
  MPI_Allgather(&mine, sizeof(RankIdentity), MPI_BYTE, ranks.data(), sizeof(RankIdentity), MPI_BYTE, world);

  ProgramGroups groups;
  groups.split_by_appnum = appnum_separates_roles(ranks);
  const std::vector<int> colours = program_colours(ranks, groups.split_by_appnum);
  const int programs = *std::max_element(colours.begin(), colours.end()) + 1;
  if (programs > 2) {
    std::string roles;
    for (int c = 0; c < programs; ++c) {
      const auto first = std::find(colours.begin(), colours.end(), c) - colours.begin();
      roles += (c ? ", " : "") + role_of(ranks[static_cast<std::size_t>(first)]);
    }
    throw std::runtime_error("the MPI job holds " + std::to_string(programs) + " programs (" + roles +
                             "); a coupled job has exactly two, a fluid and a structure program");
  }
  const int my_colour = colours[static_cast<std::size_t>(world_rank)];
  MPI_Comm_split(world, my_colour, world_rank, &groups.local);
  if (programs == 1) return groups;

  int partner_leader = -1;
  for (int r = 0; r < world_size; ++r)
    if (colours[static_cast<std::size_t>(r)] != my_colour) {
      partner_leader = r;
      break;
    }
  groups.partner_role = role_of(ranks[static_cast<std::size_t>(partner_leader)]);
  if (groups.partner_role == role) {
    MPI_Comm_free(&groups.local);
    throw std::runtime_error("the MPI job holds two programs of role '" + role +
                             "'; a coupled job has one fluid and one structure program");
  }
  MPI_Intercomm_create(groups.local, 0, world, partner_leader, intercomm_tag, &groups.partner);
  return groups;
}

void free_program_groups(ProgramGroups& groups) {
  if (groups.partner != MPI_COMM_NULL) MPI_Comm_free(&groups.partner);
  if (groups.local != MPI_COMM_NULL) MPI_Comm_free(&groups.local);
}

}  // namespace tankfsi
