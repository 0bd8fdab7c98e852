// The C interface (include/tankfsi/coupling.h) over the C++ Participant.
#include "tankfsi/coupling.h"

#include <algorithm>
#include <iostream>
#include <stdexcept>
#include <memory>
#include <string>

#include "common/config/case_config.hpp"
#include "common/config/case_schema.hpp"
#include "common/parallel/program_groups.hpp"
#include "coupling/participant.hpp"

struct tankfsi_participant {
  tankfsi::ProgramGroups groups;
  std::unique_ptr<tankfsi::coupling::Participant> participant;
  std::string error;
  std::vector<int> triangles;
};

namespace {

std::string create_error;  // the last failed create

using tankfsi::coupling::Field;

Field field_of(int field) {
  switch (field) {
    case TANKFSI_FORCE: return Field::force;
    case TANKFSI_DISPLACEMENT: return Field::displacement;
    case TANKFSI_VELOCITY: return Field::velocity;
    default: throw std::invalid_argument("unknown field " + std::to_string(field));
  }
}

// Runs `call`, turning an exception into a status and the participant's error.
template <typename Call>
int guarded(const tankfsi_participant* p, Call&& call) {
  try {
    call();
    return 0;
  } catch (const std::exception& e) {
    if (p) const_cast<tankfsi_participant*>(p)->error = e.what();
    return 1;
  }
}

}  // namespace

extern "C" {

int tankfsi_participant_create(int side, const char* case_file, MPI_Comm world, tankfsi_participant** participant) {
  *participant = nullptr;
  auto p = std::make_unique<tankfsi_participant>();
  const auto coupling_side = side == TANKFSI_FLUID ? tankfsi::coupling::Side::fluid : tankfsi::coupling::Side::structure;
  try {
    if (side != TANKFSI_FLUID && side != TANKFSI_STRUCTURE) throw std::invalid_argument("side must be TANKFSI_FLUID or TANKFSI_STRUCTURE");
    // The split is collective over the world: make it before anything can fail
    // on one rank only.
    p->groups = tankfsi::split_program_groups(world, tankfsi::coupling::side_name(coupling_side));
    if (p->groups.partner == MPI_COMM_NULL) throw std::runtime_error("no partner program in this MPI job");
    const auto config = tankfsi::CaseConfig::load(case_file, {}, tankfsi::case_schema());
    p->participant = std::make_unique<tankfsi::coupling::Participant>(
        coupling_side, tankfsi::coupling::read_coupling_settings(config), p->groups.local, p->groups.partner,
        tankfsi::coupling::case_fingerprints(config));
  } catch (const std::exception& e) {
    create_error = e.what();
    tankfsi::free_program_groups(p->groups);
    return 1;
  }
  *participant = p.release();
  return 0;
}

int tankfsi_participant_create_f(int side, const char* case_file, MPI_Fint world, tankfsi_participant** participant) {
  return tankfsi_participant_create(side, case_file, MPI_Comm_f2c(world), participant);
}

void tankfsi_participant_destroy(tankfsi_participant* participant) {
  if (!participant) return;
  participant->participant.reset();
  tankfsi::free_program_groups(participant->groups);
  delete participant;
}

const char* tankfsi_last_error(const tankfsi_participant* participant) {
  return participant ? participant->error.c_str() : create_error.c_str();
}

void tankfsi_abort(const char* message, int status) {
  std::cerr << (message ? message : "coupled run stopped") << std::endl;
  MPI_Abort(MPI_COMM_WORLD, status);
}

MPI_Comm tankfsi_local_comm(const tankfsi_participant* p) { return p->groups.local; }
MPI_Fint tankfsi_local_comm_f(const tankfsi_participant* p) { return MPI_Comm_c2f(p->groups.local); }

int tankfsi_set_interface(tankfsi_participant* p, size_t vertex_count, const int64_t* ids, const double* coordinates,
                          size_t triangle_count, const int64_t* triangles) {
  return guarded(p, [&] {
    std::vector<std::int64_t> id_list(ids, ids + vertex_count);
    std::vector<double> xyz(coordinates, coordinates + 3 * vertex_count);
    std::vector<std::array<std::int64_t, 3>> tri(triangle_count);
    for (size_t t = 0; t < triangle_count; ++t) tri[t] = {triangles[3 * t], triangles[3 * t + 1], triangles[3 * t + 2]};
    p->participant->set_interface(id_list, xyz, tri);
  });
}

int tankfsi_exchange_interface(tankfsi_participant* p) { return guarded(p, [&] { p->participant->exchange_interface(); }); }

size_t tankfsi_vertex_count(const tankfsi_participant* p) { return p->participant->interface_mesh().vertex_count(); }
const int64_t* tankfsi_vertex_ids(const tankfsi_participant* p) { return p->participant->interface_mesh().ids.data(); }
const double* tankfsi_vertex_coordinates(const tankfsi_participant* p) {
  return p->participant->interface_mesh().coordinates.data();
}
size_t tankfsi_triangle_count(const tankfsi_participant* p) { return p->participant->interface_mesh().triangles.size(); }
int tankfsi_triangles(const tankfsi_participant* p, int* vertex_indices) {
  return guarded(p, [&] {
    for (const auto& t : p->participant->interface_mesh().triangles) {
      *vertex_indices++ = t[0];
      *vertex_indices++ = t[1];
      *vertex_indices++ = t[2];
    }
  });
}

int tankfsi_initialize(tankfsi_participant* p) { return guarded(p, [&] { p->participant->initialize(); }); }
int tankfsi_is_ongoing(const tankfsi_participant* p) { return p->participant->is_ongoing() ? 1 : 0; }
double tankfsi_time(const tankfsi_participant* p) { return p->participant->time(); }
double tankfsi_max_time_step(const tankfsi_participant* p) { return p->participant->max_time_step(); }

int tankfsi_read(const tankfsi_participant* p, int field, double relative_dt, double* values, size_t count) {
  return guarded(p, [&] { p->participant->read(field_of(field), relative_dt, std::span<double>(values, count)); });
}
int tankfsi_write(tankfsi_participant* p, int field, const double* values, size_t count) {
  return guarded(p, [&] { p->participant->write(field_of(field), std::span<const double>(values, count)); });
}
int tankfsi_advance(tankfsi_participant* p, double dt) { return guarded(p, [&] { p->participant->advance(dt); }); }
int tankfsi_requires_writing_checkpoint(tankfsi_participant* p) {
  return p->participant->requires_writing_checkpoint() ? 1 : 0;
}
int tankfsi_requires_reading_checkpoint(tankfsi_participant* p) {
  return p->participant->requires_reading_checkpoint() ? 1 : 0;
}
int tankfsi_window_completed(const tankfsi_participant* p) { return p->participant->window_completed() ? 1 : 0; }
int tankfsi_finalize(tankfsi_participant* p) { return guarded(p, [&] { p->participant->finalize(); }); }

namespace {
void copy_exactly(const std::vector<double>& from, double* to, size_t count, const char* what) {
  if (count != from.size())
    throw std::invalid_argument(std::string(what) + ": array of " + std::to_string(count) + " values, expected " +
                                std::to_string(from.size()));
  std::copy(from.begin(), from.end(), to);
}
}  // namespace

int tankfsi_interface_normals(const tankfsi_participant* p, double* normals, size_t count) {
  return guarded(p, [&] { copy_exactly(p->participant->interface_normals(), normals, count, "tankfsi_interface_normals"); });
}
int tankfsi_write_added_mass(tankfsi_participant* p, const double* matrix, size_t count) {
  return guarded(p, [&] { p->participant->write_added_mass(std::span<const double>(matrix, count)); });
}
int tankfsi_added_mass(const tankfsi_participant* p, double* normals, size_t normal_count, double* rows,
                       size_t row_count) {
  return guarded(p, [&] {
    const auto operator_rows = p->participant->added_mass();
    copy_exactly(operator_rows.normals, normals, normal_count, "tankfsi_added_mass (normals)");
    copy_exactly(operator_rows.rows, rows, row_count, "tankfsi_added_mass (rows)");
  });
}

}  // extern "C"
