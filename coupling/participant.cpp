// Participant: initialisation, messages, data and the public class (participant_impl.hpp).
#include "coupling/participant_impl.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/run/checkpoint_series.hpp"
#include "coupling/added_mass/added_mass.hpp"

namespace tankfsi::coupling {

namespace {

std::string describe_mismatch(const std::map<std::string, std::string>& mine,
                              const std::map<std::string, std::string>& theirs, const std::string& prefix,
                              Side side) {
  std::string text;
  std::map<std::string, std::string> keys;
  for (const auto& [k, v] : mine) keys[k];
  for (const auto& [k, v] : theirs) keys[k];
  for (const auto& [key, unused] : keys) {
    if (key.rfind(prefix, 0) != 0) continue;
    const auto a = mine.find(key);
    const auto b = theirs.find(key);
    const std::string va = a == mine.end() ? "(none)" : a->second;
    const std::string vb = b == theirs.end() ? "(none)" : b->second;
    if (va == vb) continue;
    text += "\n  " + key.substr(prefix.size()) + ": " + side_name(side) + " " + va + ", " + side_name(other(side)) +
            " " + vb;
  }
  return text;
}

}  // namespace

// ---- initialisation -------------------------------------------------------

void Participant::Impl::handshake() {
  std::map<std::string, std::string> hello;
  for (const auto& [key, value] : settings_.as_map()) hello["setting." + key] = value;
  for (const auto& [key, value] : fingerprints_) hello["case." + key] = value;
  const auto theirs = link_.exchange_hello(hello);

  std::string problems;
  if (theirs.count("protocol") == 0 || theirs.at("protocol") != "tankfsi-coupling")
    throw CouplingError(link_.partner_name() + " does not speak the tankfsi coupling protocol");
  if (theirs.at("protocol.major") != std::to_string(protocol_major))
    problems += "\n  protocol version: " + std::string(side_name(side_)) + " " + std::to_string(protocol_major) + "." +
                std::to_string(protocol_minor) + ", partner " + theirs.at("protocol.major") + "." +
                theirs.at("protocol.minor");
  if (theirs.at("side") == side_name(side_))
    problems += "\n  both programs are on the " + std::string(side_name(side_)) + " side";
  std::map<std::string, std::string> mine = hello;
  problems += describe_mismatch(mine, theirs, "setting.", side_);
  const bool both_fingerprinted = !fingerprints_.empty() && std::any_of(theirs.begin(), theirs.end(), [](const auto& entry) {
                         return entry.first.rfind("case.", 0) == 0;
                       });
  if (both_fingerprinted) {
    const std::string sections = describe_mismatch(mine, theirs, "case.", side_);
    if (!sections.empty()) {
      std::string names;
      std::istringstream lines(sections);
      std::string line;
      while (std::getline(lines, line))
        if (const auto colon = line.find(':'); colon != std::string::npos)
          names += (names.empty() ? "" : ", ") + line.substr(2, colon - 2);
      problems += "\n  the programs read different cases (sections that differ: " + names + ")";
    }
  }
  if (!problems.empty())
    throw CouplingError("the " + std::string(side_name(side_)) + " and " + side_name(other(side_)) +
                        " programs do not agree:" + problems);
}

void Participant::Impl::exchange_interface() {
  if (exchange_) throw CouplingError("exchange_interface() called twice");
  if (side_ == Side::structure && !declared_)
    throw CouplingError("the structure side must call set_interface() before the interface is exchanged");
  const auto start = Clock::now();
  const double wait_before = link_.wait_seconds();
  handshake();
  if (side_ == Side::structure)
    exchange_ = std::make_unique<InterfaceExchange>(link_, declared_ids_, declared_coordinates_, declared_triangles_);
  else
    exchange_ = std::make_unique<InterfaceExchange>(link_);
  work_seconds_ += std::chrono::duration<double>(Clock::now() - start).count() - (link_.wait_seconds() - wait_before);
}

void Participant::Impl::initialize() {
  if (initialized_) throw CouplingError("initialize() called twice");
  if (!exchange_) exchange_interface();
  const auto start = Clock::now();
  const double wait_before = link_.wait_seconds();
  const std::size_t count = value_count();
  if (!initial_values_.empty() && initial_values_.size() != count)
    throw CouplingError("initial data of " + std::to_string(initial_values_.size()) + " values, expected " +
                        std::to_string(count));
  if (initial_values_.empty()) initial_values_.assign(count, 0.0);
  start_data();
  exchange_added_mass();
  if (side_ == Side::fluid) initial_values_ = to_mesh(initial_values_);

  // Initial data: each program sends its initial output, receives the
  // partner's, and starts its own input from it.
  if (side_ == Side::fluid) {
    const std::vector<double> slice = exchange_->reduce_to_slice(initial_values_);
    send_part(slice, 0, verdict_accept);
    last_output_ = slice;
  } else {
    displacement_ = initial_values_;
    send_part(displacement_, 0, verdict_accept);
    last_output_ = displacement_;
  }
  const Received initial = receive_part(0, 0, "initial " + partner_data_name());
  if (side_ == Side::fluid) {
    path_ = DisplacementPath(exchange_->gather_slices(initial.part));
  } else {
    ramp_ = LoadRamp(initial.part);
    force_input_ = initial.part;
  }
  previous_output_ = last_output_;

  if (!settings_.is_implicit()) {
    aim(initial.part);
    if (!lags(settings_, side_)) aim(receive_part(1, 0, partner_data_name() + " of window 1").part);
  } else if (!controller_) {
    aim(receive_part(0, 0, "the first coupling input").part);
  } else {
    // The first guess of the follower's input is its initial value; in
    // parallel mode the controller's own input starts from the partner's.
    const bool parallel = settings_.implicit_mode == ImplicitMode::parallel;
    sent_input_ = parallel ? displacement_ : last_output_;
    if (parallel) sent_input_.insert(sent_input_.end(), initial.part.begin(), initial.part.end());
    const std::size_t follower_size = parallel ? displacement_.size() : sent_input_.size();
    send_part(std::vector<double>(sent_input_.begin(), sent_input_.begin() + static_cast<long>(follower_size)), 0,
              verdict_accept);
    if (parallel)
      aim(initial.part);
    else
      aim(receive_part(1, 0, partner_data_name() + " of window 1").part);
    if (parallel) last_output_ = previous_output_ = sent_input_;  // x̂_0 = [d_0, F_0]
  }
  write_checkpoint_ = settings_.is_implicit();
  work_seconds_ += std::chrono::duration<double>(Clock::now() - start).count() - (link_.wait_seconds() - wait_before);
}

void Participant::Impl::exchange_added_mass() {
  if (!settings_.added_mass_operator) return;
  const std::size_t n = exchange_->global_vertex_count();
  const std::size_t values = 3 * n;
  if (side_ == Side::structure) {
    added_mass_ = exchange_->receive_part(tag_added_mass, "the fluid's added-mass operator", n);
    // The normals: from fluid rank 0 to structure rank 0, then to every structure rank.
    added_mass_normals_.assign(values, 0.0);
    int rank = 0;
    MPI_Comm_rank(link_.local(), &rank);
    if (rank == 0) {
      std::vector<MPI_Request> request(1);
      MPI_Irecv(added_mass_normals_.data(), static_cast<int>(values), MPI_DOUBLE, 0, tag_added_mass_normals,
                link_.inter(), request.data());
      link_.wait(request, "the normals of the fluid's added-mass operator");
    }
    MPI_Bcast(added_mass_normals_.data(), static_cast<int>(values), MPI_DOUBLE, 0, link_.local());
    return;
  }
  if (added_mass_.size() != n * n)
    throw CouplingError(added_mass_.empty()
                            ? "coupling.added_mass is computed: the fluid must write_added_mass() before initialize()"
                            : "added-mass operator of " + std::to_string(added_mass_.size()) + " values, expected " +
                                  std::to_string(n) + " x " + std::to_string(n));
  MPI_Allreduce(MPI_IN_PLACE, added_mass_.data(), static_cast<int>(added_mass_.size()), MPI_DOUBLE, MPI_SUM,
                link_.local());
  symmetrise(added_mass_, n);
  added_mass_normals_ = vertex_normals(exchange_->mesh());
  // Each structure rank gets the rows of its vertices: the slice's rows go
  // out as the forces do, n values per vertex instead of 3.
  const std::size_t first = exchange_->slice_offset() / 3;
  const auto slice_rows = std::span<const double>(added_mass_).subspan(first * n, exchange_->part_size() / 3 * n);
  exchange_->post_sends(slice_rows, tag_added_mass, n);
  int rank = 0;
  MPI_Comm_rank(link_.local(), &rank);
  if (rank == 0) {
    std::vector<MPI_Request> request(1);
    MPI_Isend(added_mass_normals_.data(), static_cast<int>(values), MPI_DOUBLE, 0, tag_added_mass_normals,
              link_.inter(), request.data());
    link_.wait(request, "the structure to take the added-mass operator's normals");
  }
  previous_wall_velocity_.assign(values, 0.0);  // the walls start at rest
}

void Participant::Impl::start_data() {
  initialized_ = true;
  if (side_ == Side::fluid) {
    const std::size_t mesh_count = 3 * exchange_->global_vertex_count();
    if (!own_points_.empty()) mapping_ = std::make_unique<NearestProjection>(exchange_->mesh(), own_points_);
    step_force_.assign(mesh_count, 0.0);
    force_average_ = WindowAverage(mesh_count);
  }
  if (controller_) acceleration_ = make_acceleration(settings_, link_.local());
  next_restart_time_ = next_output_time(window_start_, restart_interval_);
}

// ---- messages -------------------------------------------------------------

std::vector<double> Participant::Impl::output_part() {
  if (side_ == Side::fluid) {
    std::vector<double> slice = exchange_->reduce_to_slice(force_average_.average(window_length()));
    return slice;
  }
  if (!displacement_written_)
    throw CouplingError("window " + std::to_string(window_) +
                        " ended without write(displacement) since its start: the structure must write its "
                        "displacements at least once per window");
  return displacement_;
}

void Participant::Impl::send_part(const std::vector<double>& part, int window, std::int32_t verdict) {
  Control control;
  control.window = window;
  control.iteration = window == 0 ? 0 : iteration_;
  control.converged = verdict;
  control.time = window_start_ + elapsed_;
  link_.send_control(control);
  exchange_->post_sends(part, my_tag());
}

Participant::Impl::Received Participant::Impl::receive_part(int expected_window, int expected_iteration,
                                                            const std::string& what) {
  Received r;
  r.control = link_.receive_control(what);
  if (r.control.window != expected_window || r.control.iteration != expected_iteration)
    throw CouplingError("protocol out of step: the " + std::string(side_name(side_)) + " program expected " + what +
                        " of window " + std::to_string(expected_window) + " iteration " +
                        std::to_string(expected_iteration) + " and received window " +
                        std::to_string(r.control.window) + " iteration " + std::to_string(r.control.iteration) +
                        " (do both programs use the same coupling settings?)");
  r.part = exchange_->receive_part(partner_tag(), what);
  return r;
}

void Participant::Impl::aim(const std::vector<double>& part) {
  if (side_ == Side::fluid) {
    path_.aim(exchange_->gather_slices(part));
  } else {
    force_input_ = part;
    if (settings_.hold_window_average) ramp_.hold(part);
    else ramp_.aim(part, settings_.ramp_chi);
  }
}

// ---- data -----------------------------------------------------------------

void Participant::Impl::read(Field field, double relative_dt, std::span<double> values) const {
  require_initialized("read");
  const bool fluid_field = field != Field::force;
  if (fluid_field != (side_ == Side::fluid))
    throw CouplingError(std::string("read: the ") + side_name(side_) + " side does not read " +
                        (field == Field::force ? "forces" : "displacements or velocities"));
  if (field == Field::velocity_change && !settings_.added_mass_operator)
    throw CouplingError("read: the wall velocity's change is read with coupling.added_mass: computed only");
  if (values.size() != value_count())
    throw CouplingError("read: array of " + std::to_string(values.size()) + " values, expected " +
                        std::to_string(value_count()));
  const double fraction = std::clamp((elapsed_ + relative_dt) / window_length(), 0.0, 1.0);
  if (field == Field::force) {
    ramp_.at(fraction, values);
    return;
  }
  std::span<double> on_mesh = values;
  if (mapping_) {
    mesh_scratch_.resize(3 * exchange_->global_vertex_count());
    on_mesh = mesh_scratch_;
  }
  if (field == Field::displacement) {
    path_.at(fraction, on_mesh);
  } else {
    path_.velocity(window_length(), on_mesh);
    if (field == Field::velocity_change)
      for (std::size_t k = 0; k < on_mesh.size(); ++k) on_mesh[k] -= previous_wall_velocity_[k];
  }
  if (mapping_) mapping_->consistent(on_mesh, values);
}

void Participant::Impl::write(Field field, std::span<const double> values) {
  const Field expected = side_ == Side::fluid ? Field::force : Field::displacement;
  if (field != expected)
    throw CouplingError(std::string("write: the ") + side_name(side_) + " side writes " +
                        (expected == Field::force ? "forces" : "displacements"));
  if (!initialized_) {  // initial data
    if (side_ == Side::structure ? !declared_ : !exchange_)
      throw CouplingError("write: initial data before the interface is known (set_interface / exchange_interface)");
    initial_values_.assign(values.begin(), values.end());
    return;
  }
  if (values.size() != value_count())
    throw CouplingError("write: array of " + std::to_string(values.size()) + " values, expected " +
                        std::to_string(value_count()));
  if (side_ == Side::fluid) {
    if (mapping_)
      mapping_->conservative(values, step_force_);
    else
      step_force_.assign(values.begin(), values.end());
    step_force_written_ = true;
  } else {
    displacement_.assign(values.begin(), values.end());
    displacement_written_ = true;
  }
}

void Participant::Impl::finalize() {
  if (finalized_ || !initialized_) return;
  finalized_ = true;
  exchange_->finish_sends("the partner to take the last interface data");
  Control done;
  done.kind = static_cast<std::int32_t>(ControlKind::finalize);
  done.window = window_ - 1;
  done.time = time();
  link_.send_control(done);
  link_.receive_finalize();
}

// ---- the public class ---------------------------------------------------------

Participant::Participant(Side side, const CouplingSettings& settings, MPI_Comm local, MPI_Comm partner,
                         std::map<std::string, std::string> fingerprints)
    : impl_(std::make_unique<Impl>(side, settings, local, partner, std::move(fingerprints))) {}
Participant::~Participant() = default;

void Participant::set_interface(const std::vector<std::int64_t>& ids, const std::vector<double>& coordinates,
                                const std::vector<std::array<std::int64_t, 3>>& triangles) {
  impl_->set_interface(ids, coordinates, triangles);
}
void Participant::set_own_vertices(std::vector<double> coordinates) { impl_->set_own_vertices(std::move(coordinates)); }
double Participant::max_mapping_distance() const { return impl_->mapping_ ? impl_->mapping_->max_distance() : 0.0; }
void Participant::exchange_interface() { impl_->exchange_interface(); }
void Participant::initialize() { impl_->initialize(); }
const InterfaceMesh& Participant::interface_mesh() const { return impl_->mesh(); }
std::size_t Participant::value_count() const { return impl_->value_count(); }
bool Participant::is_ongoing() const { return impl_->is_ongoing(); }
double Participant::time() const { return impl_->time(); }
double Participant::max_time_step() const { return impl_->max_time_step(); }
void Participant::read(Field field, double relative_dt, std::span<double> values) const {
  impl_->read(field, relative_dt, values);
}
void Participant::write(Field field, std::span<const double> values) { impl_->write(field, values); }
void Participant::advance(double dt) { impl_->advance(dt); }
bool Participant::requires_writing_checkpoint() { return impl_->take(impl_->write_checkpoint_); }
bool Participant::requires_reading_checkpoint() { return impl_->take(impl_->read_checkpoint_); }
bool Participant::window_completed() const { return impl_->window_completed_; }
bool Participant::at_window_start() const { return impl_->elapsed_ == 0.0; }
const std::vector<WindowReport>& Participant::window_reports() const { return impl_->reports_; }
CouplingTimings Participant::timings() const { return {impl_->link_.wait_seconds(), impl_->work_seconds_}; }
void Participant::finalize() { impl_->finalize(); }
std::vector<double> Participant::interface_normals() const {
  if (impl_->side_ != Side::fluid) throw CouplingError("interface_normals: the fluid side's (the structure has added_mass())");
  return vertex_normals(impl_->mesh());
}
void Participant::write_added_mass(std::span<const double> matrix) {
  if (impl_->side_ != Side::fluid || !impl_->settings_.added_mass_operator || impl_->initialized_ || !impl_->exchange_)
    throw CouplingError("write_added_mass: the fluid's, with coupling.added_mass: computed, after "
                        "exchange_interface() and before initialize()");
  impl_->added_mass_.assign(matrix.begin(), matrix.end());
}
AddedMassRows Participant::added_mass() const {
  if (impl_->side_ != Side::structure || !impl_->settings_.added_mass_operator || !impl_->initialized_)
    throw CouplingError("added_mass: the structure's, with coupling.added_mass: computed, after initialize()");
  return {impl_->added_mass_normals_, impl_->added_mass_};
}
void Participant::set_restart_interval(double seconds) {
  if (impl_->initialized_) throw CouplingError("set_restart_interval: after initialize()");
  if (!(seconds >= 0.0)) throw CouplingError("set_restart_interval: the interval must be 0 or positive");
  impl_->restart_interval_ = seconds;
}
void Participant::request_stop() { impl_->stop_requested_ = true; }
bool Participant::restart_point_due() { return impl_->take(impl_->restart_point_due_); }
int Participant::stop_signal() const { return impl_->stop_signal_; }
const CouplingRestartState& Participant::restart_state() const { return impl_->restart_state_; }
void Participant::resume(const CouplingRestartState& state) { impl_->resume(state); }

}  // namespace tankfsi::coupling
