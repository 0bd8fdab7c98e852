#include "coupling/participant.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "common/io/exact_number.hpp"
#include "common/run/checkpoint_series.hpp"
#include "common/run/stop_signal.hpp"
#include "coupling/acceleration/acceleration.hpp"
#include "coupling/added_mass/added_mass.hpp"
#include "coupling/interface/interface_exchange.hpp"
#include "coupling/mapping/nearest_projection.hpp"
#include "coupling/partnership/partner_link.hpp"
#include "coupling/schemes/schedule.hpp"
#include "coupling/time/window_interpolation.hpp"

namespace tankfsi::coupling {

namespace {

using Clock = std::chrono::steady_clock;

// Window ends within this fraction of its length count as reached: sub-steps
// that add up to dt_c in floating point land a few ulps short or long.
constexpr double window_end_tolerance = 1e-9;

// A window's verdict in the control record (PROTOCOL.md, "Control").
constexpr std::int32_t verdict_repeat = 0;
constexpr std::int32_t verdict_accept = 1;
constexpr std::int32_t verdict_stop = -1;

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

double norm(MPI_Comm comm, std::span<const double> v) { return std::sqrt(weighted_dot(comm, v, v, {})); }

std::array<double, 3> component_sums(MPI_Comm comm, std::span<const double> values, double factor) {
  std::array<double, 3> local{};
  for (std::size_t i = 0; i < values.size(); ++i) local[i % 3] += values[i] * factor;
  std::array<double, 3> global{};
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

}  // namespace

class Participant::Impl {
 public:
  Impl(Side side, const CouplingSettings& settings, MPI_Comm local, MPI_Comm partner,
       std::map<std::string, std::string> fingerprints)
      : side_(side), settings_(settings), link_(local, partner, side, settings.timeout),
        fingerprints_(std::move(fingerprints)), controller_(controls(settings, side)) {
    settings_.check();
  }

  void set_interface(const std::vector<std::int64_t>& ids, const std::vector<double>& coordinates,
                     const std::vector<std::array<std::int64_t, 3>>& triangles) {
    if (side_ != Side::structure) throw CouplingError("set_interface: only the structure side declares the interface");
    if (initialized_) throw CouplingError("set_interface: after initialize()");
    declared_ids_ = ids;
    declared_coordinates_ = coordinates;
    declared_triangles_ = triangles;
    declared_ = true;
  }

  void exchange_interface();
  void initialize();
  void advance(double dt);
  void read(Field field, double relative_dt, std::span<double> values) const;
  void write(Field field, std::span<const double> values);
  void finalize();

  [[nodiscard]] const InterfaceMesh& mesh() const {
    require_exchanged("interface_mesh");
    return exchange_->mesh();
  }
  [[nodiscard]] std::size_t value_count() const {
    require_exchanged("value_count");
    if (side_ == Side::structure) return exchange_->part_size();
    return own_points_.empty() ? 3 * exchange_->global_vertex_count() : own_points_.size();
  }
  void set_own_vertices(std::vector<double> coordinates) {
    if (side_ != Side::fluid) throw CouplingError("set_own_vertices: only the fluid side maps onto the partner's mesh");
    if (initialized_) throw CouplingError("set_own_vertices: after initialize()");
    if (coordinates.empty() || coordinates.size() % 3 != 0)
      throw CouplingError("set_own_vertices: 3 coordinates per vertex expected, got " + std::to_string(coordinates.size()));
    own_points_ = std::move(coordinates);
  }
  /// Fluid: own values -> the whole mesh's (partial) values.
  [[nodiscard]] std::vector<double> to_mesh(std::span<const double> own) const {
    if (!mapping_) return {own.begin(), own.end()};
    std::vector<double> on_mesh(3 * exchange_->global_vertex_count());
    mapping_->conservative(own, on_mesh);
    return on_mesh;
  }
  [[nodiscard]] bool is_ongoing() const {
    return window_start_ < settings_.end_time - window_end_tolerance * settings_.time_window;
  }
  [[nodiscard]] double time() const { return window_start_ + elapsed_; }
  [[nodiscard]] double max_time_step() const { return window_length() - elapsed_; }

  bool take(bool& flag) {
    const bool was = flag;
    flag = false;
    return was;
  }

  Side side_;
  CouplingSettings settings_;
  PartnerLink link_;
  std::map<std::string, std::string> fingerprints_;
  bool controller_;
  std::unique_ptr<InterfaceExchange> exchange_;
  std::unique_ptr<Acceleration> acceleration_;

  bool declared_ = false;
  std::vector<std::int64_t> declared_ids_;
  std::vector<double> declared_coordinates_;
  std::vector<std::array<std::int64_t, 3>> declared_triangles_;

  bool initialized_ = false;
  bool finalized_ = false;
  int window_ = 1;
  int iteration_ = 0;
  double window_start_ = 0.0;
  double elapsed_ = 0.0;

  // Fluid: forces of the step to come, their window average, the wall path.
  std::vector<double> step_force_;
  bool step_force_written_ = false;
  WindowAverage force_average_;
  DisplacementPath path_;
  // Structure: displacements written, the ramp of the force read.
  std::vector<double> displacement_;
  bool displacement_written_ = false;
  LoadRamp ramp_;
  std::vector<double> force_input_;  ///< the F̄ the ramp aims at (eq 17)
  // Initial data written before initialize().
  std::vector<double> initial_values_;
  // The added-mass operator (coupling.added_mass: computed; added_mass.hpp):
  // fluid, the whole matrix (written as partial sums, then summed) and the
  // wall velocity of the last accepted window (whole mesh), which the next
  // window's change is taken from; structure, the rows of its vertices; both,
  // the normals of every vertex (ascending id order).
  std::vector<double> added_mass_;
  std::vector<double> added_mass_normals_;
  std::vector<double> previous_wall_velocity_;
  // Fluid with its own wall vertices: the mapping onto the partner's mesh.
  std::vector<double> own_points_;
  std::unique_ptr<NearestProjection> mapping_;
  mutable std::vector<double> mesh_scratch_;

  // Implicit controller: the input it sent (or, parallel, also its own), the
  // converged outputs of the last two windows (for the next window's guess).
  std::vector<double> sent_input_;
  std::vector<double> previous_output_;
  std::vector<double> last_output_;

  bool write_checkpoint_ = false;
  bool read_checkpoint_ = false;
  bool window_completed_ = false;

  // Restart points (PROTOCOL.md, "Window ends").
  double restart_interval_ = 0.0;
  double next_restart_time_ = std::numeric_limits<double>::infinity();
  bool stop_requested_ = false;
  bool restart_agreed_ = false;     ///< at the window end being completed
  bool restart_point_due_ = false;  ///< for restart_point_due()
  bool stopped_ = false;
  int stop_signal_ = 0;
  CouplingRestartState restart_state_;
  std::vector<double> last_output_part_;  ///< this program's output of the last window (its distributed part)

  void resume(const CouplingRestartState& state);
  std::vector<WindowReport> reports_;
  double work_seconds_ = 0.0;

 private:
  void require_exchanged(const char* what) const {
    if (!exchange_) throw CouplingError(std::string(what) + ": call exchange_interface() or initialize() first");
  }
  void require_initialized(const char* what) const {
    if (!initialized_) throw CouplingError(std::string(what) + ": call initialize() first");
  }
  [[nodiscard]] double window_length() const {
    return std::min(settings_.time_window, settings_.end_time - window_start_);
  }
  [[nodiscard]] bool last_window() const {
    return window_start_ + window_length() >= settings_.end_time - window_end_tolerance * settings_.time_window;
  }
  [[nodiscard]] int my_tag() const { return side_ == Side::fluid ? tag_force : tag_displacement; }
  [[nodiscard]] int partner_tag() const { return side_ == Side::fluid ? tag_displacement : tag_force; }
  [[nodiscard]] std::string partner_data_name() const {
    return side_ == Side::fluid ? "displacements" : "forces";
  }

  void handshake();
  /// Everything initialize() and resume() set up before the first exchange.
  void start_data();
  /// The window-end records (not after the last window, where both write a
  /// checkpoint anyway): sets restart_agreed_ and stop_signal_.
  void agree_on_window_end(bool last);
  /// Fills restart_state_ (in accept(), between the window's end and the next input).
  void capture_restart_state();
  /// Fluid: a whole-interface array from a slice, and back.
  [[nodiscard]] std::vector<double> whole(const std::vector<double>& part) const;
  [[nodiscard]] std::vector<double> part_of(const CouplingRestartState& state, const std::string& name) const;
  /// This program's output of the window in its distributed part: fluid, the
  /// force average on its slice; structure, its displacements.
  [[nodiscard]] std::vector<double> output_part();
  /// Sends a part as the message of the end of `window` (0: initialize) and
  /// the current iteration, with the controller's verdict.
  void send_part(const std::vector<double>& part, int window, std::int32_t verdict);
  struct Received {
    Control control;
    std::vector<double> part;
  };
  Received receive_part(int expected_window, int expected_iteration, const std::string& what);
  /// The input the program reads from, made from a received part: fluid, the
  /// whole displacement array; structure, its forces.
  void aim(const std::vector<double>& part);
  /// initialize(): the fluid's added-mass operator to the structure (PROTOCOL.md, "Added mass").
  void exchange_added_mass();
  void complete_window();
  void complete_explicit();
  void complete_follower();
  void complete_controller();
  void accept(const std::vector<double>& next_input_part, int iterations, bool converged, double residual_d,
              double residual_f);
  void repeat(const std::vector<double>& next_input_part);
  [[nodiscard]] std::vector<double> predicted(const std::vector<double>& last, const std::vector<double>& previous) const;
};

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

// ---- restarts ---------------------------------------------------------------

void Participant::Impl::agree_on_window_end(bool last) {
  const double end = window_start_ + window_length();
  if (last) {
    restart_agreed_ = true;  // the end state: both write it, nothing to agree
    return;
  }
  // This program's wishes, over its ranks: a checkpoint due, a stop (signal number, or -1 when asked).
  std::array<int, 3> mine{end >= next_restart_time_ * (1 - 1e-12) ? 1 : 0, received_stop_signal(),
                          stop_requested_ ? 1 : 0};
  MPI_Allreduce(MPI_IN_PLACE, mine.data(), 3, MPI_INT, MPI_MAX, link_.local());
  const bool my_stop = mine[1] != 0 || mine[2] != 0;
  Control record;
  record.kind = static_cast<std::int32_t>(ControlKind::window_end);
  record.window = window_;
  record.iteration = mine[1] != 0 ? mine[1] : (my_stop ? -1 : 0);
  record.converged = (mine[0] != 0 ? 1 : 0) | (my_stop ? 2 : 0);
  record.time = end;
  link_.send_control(record);
  const Control theirs = link_.receive_window_end("the window-end record of window " + std::to_string(window_));
  if (theirs.window != window_)
    throw CouplingError("protocol out of step: the " + std::string(side_name(side_)) + " program ended window " +
                        std::to_string(window_) + ", its partner window " + std::to_string(theirs.window));
  const bool their_stop = (theirs.converged & 2) != 0;
  restart_agreed_ = mine[0] != 0 || (theirs.converged & 1) != 0 || my_stop || their_stop;
  stop_signal_ = my_stop ? record.iteration : their_stop ? theirs.iteration : 0;
}

std::vector<double> Participant::Impl::whole(const std::vector<double>& part) const {
  return side_ == Side::fluid ? exchange_->gather_slices(part) : part;
}

std::vector<double> Participant::Impl::part_of(const CouplingRestartState& state, const std::string& name) const {
  const auto found = state.arrays.find(name);
  if (found == state.arrays.end()) throw CouplingError("restart state without '" + name + "'");
  if (side_ != Side::fluid) return found->second;
  const std::size_t whole_size = 3 * exchange_->global_vertex_count();
  if (found->second.size() != whole_size)
    throw CouplingError("restart state '" + name + "' of " + std::to_string(found->second.size()) +
                        " values for an interface of " + std::to_string(whole_size));
  const auto begin = found->second.begin() + static_cast<long>(exchange_->slice_offset());
  return {begin, begin + static_cast<long>(exchange_->part_size())};
}

void Participant::Impl::capture_restart_state() {
  CouplingRestartState& state = restart_state_;
  state = CouplingRestartState{};
  state.window = window_;
  state.window_start = window_start_;
  state.reports = reports_;
  state.arrays["input_start"] = side_ == Side::fluid ? path_.start() : ramp_.start();
  state.arrays["last_output"] = whole(last_output_part_);
  if (settings_.added_mass_operator) {
    // Fluid: the whole operator (a restart may have other fluid ranks); structure: its rows.
    state.arrays["added_mass"] = added_mass_;
    state.arrays["added_mass_normals"] = added_mass_normals_;
    if (side_ == Side::fluid) state.arrays["previous_wall_velocity"] = previous_wall_velocity_;
  }
  if (controller_) {
    state.arrays["sent_input"] = whole(sent_input_);
    state.arrays["controller_last"] = whole(last_output_);
    state.arrays["controller_previous"] = whole(previous_output_);
    const Acceleration::History history = acceleration_->history();
    state.history_numbers = history.numbers;
    for (std::size_t k = 0; k < history.vectors.size(); ++k)
      state.arrays["history_" + std::to_string(k)] = whole(history.vectors[k]);
  }
}

void Participant::Impl::resume(const CouplingRestartState& state) {
  if (initialized_) throw CouplingError("resume() after initialize() or resume()");
  if (!exchange_) exchange_interface();
  const auto start = Clock::now();
  const double wait_before = link_.wait_seconds();
  window_ = state.window;
  window_start_ = state.window_start;
  reports_ = state.reports;
  start_data();
  const auto input_start = state.arrays.find("input_start");
  if (input_start == state.arrays.end()) throw CouplingError("restart state without 'input_start'");
  if (side_ == Side::fluid)
    path_ = DisplacementPath(input_start->second);
  else
    ramp_ = LoadRamp(input_start->second);
  // Each program sends the output of the window that ended again: the
  // partner takes its input for the next window from it, as at that window's end.
  last_output_part_ = part_of(state, "last_output");
  if (side_ == Side::structure) displacement_ = last_output_part_;
  if (settings_.added_mass_operator) {
    const auto array = [&](const std::string& name) {
      const auto found = state.arrays.find(name);
      if (found == state.arrays.end()) throw CouplingError("restart state without '" + name + "'");
      return found->second;
    };
    added_mass_ = array("added_mass");
    added_mass_normals_ = array("added_mass_normals");
    if (side_ == Side::fluid) previous_wall_velocity_ = array("previous_wall_velocity");
  }
  const int ended = window_ - 1;
  send_part(last_output_part_, ended, verdict_accept);
  const Received previous = receive_part(ended, 0, partner_data_name() + " of window " + std::to_string(ended));
  if (!settings_.is_implicit()) {
    if (lags(settings_, side_))
      aim(previous.part);
    else
      aim(receive_part(window_, 0, partner_data_name() + " of window " + std::to_string(window_)).part);
  } else if (!controller_) {
    aim(receive_part(ended, 0, "the coupling input of window " + std::to_string(window_)).part);
  } else {
    sent_input_ = part_of(state, "sent_input");
    last_output_ = part_of(state, "controller_last");
    previous_output_ = part_of(state, "controller_previous");
    Acceleration::History history;
    history.numbers = state.history_numbers;
    for (std::size_t k = 0; state.arrays.count("history_" + std::to_string(k)) != 0; ++k)
      history.vectors.push_back(part_of(state, "history_" + std::to_string(k)));
    acceleration_->restore_history(history);
    const bool parallel = settings_.implicit_mode == ImplicitMode::parallel;
    const std::size_t follower_size = parallel ? last_output_part_.size() : sent_input_.size();
    if (follower_size > sent_input_.size()) throw CouplingError("restart state: 'sent_input' too short");
    send_part(std::vector<double>(sent_input_.begin(), sent_input_.begin() + static_cast<long>(follower_size)), ended,
              verdict_accept);
    if (parallel)
      aim(std::vector<double>(sent_input_.begin() + static_cast<long>(follower_size), sent_input_.end()));
    else
      aim(receive_part(window_, 0, partner_data_name() + " of window " + std::to_string(window_)).part);
  }
  write_checkpoint_ = settings_.is_implicit();
  work_seconds_ += std::chrono::duration<double>(Clock::now() - start).count() - (link_.wait_seconds() - wait_before);
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

// ---- windows --------------------------------------------------------------

void Participant::Impl::advance(double dt) {
  require_initialized("advance");
  if (finalized_) throw CouplingError("advance: after finalize()");
  if (stopped_) throw CouplingError("advance: the partners agreed to stop at t = " + std::to_string(time()) + " s");
  if (!is_ongoing()) throw CouplingError("advance: the coupled run has ended (t = " + std::to_string(time()) + " s)");
  const double remaining = max_time_step();
  if (!(dt > 0) || dt > remaining * (1 + window_end_tolerance) + window_end_tolerance * settings_.time_window)
    throw CouplingError("advance(" + std::to_string(dt) + " s): the step must be positive and at most max_time_step() = " +
                        std::to_string(remaining) + " s");
  if (side_ == Side::fluid) {
    if (!step_force_written_)
      throw CouplingError("advance: the fluid must write(force) before each step (the force over that step, eq 16)");
    force_average_.add(step_force_, dt);
    step_force_written_ = false;
  }
  window_completed_ = false;
  elapsed_ += dt;
  if (elapsed_ >= window_length() * (1 - window_end_tolerance)) {
    elapsed_ = window_length();
    const auto start = Clock::now();
    const double wait_before = link_.wait_seconds();
    complete_window();
    work_seconds_ += std::chrono::duration<double>(Clock::now() - start).count() - (link_.wait_seconds() - wait_before);
  }
}

void Participant::Impl::complete_window() {
  if (!settings_.is_implicit())
    complete_explicit();
  else if (controller_)
    complete_controller();
  else
    complete_follower();
}

void Participant::Impl::complete_explicit() {
  const bool last = last_window();
  last_output_part_ = output_part();
  if (sends_output(settings_, side_, last)) send_part(last_output_part_, window_, verdict_accept);
  std::vector<double> next;
  const bool lagging = lags(settings_, side_);
  const auto receive_input = [&](int from_window) {
    next = receive_part(from_window, 0, partner_data_name() + " of window " + std::to_string(from_window)).part;
  };
  // The window-end records come where both programs have sent and taken
  // everything of this window: after the lagging side's receive, before the
  // receive of the side one window ahead (which a stop makes unnecessary).
  if (receives_input(last) && lagging) receive_input(window_);
  agree_on_window_end(last);
  if (receives_input(last) && !lagging && stop_signal_ == 0) receive_input(window_ + 1);
  accept(next, 1, true, -1, -1);
}

void Participant::Impl::complete_follower() {
  last_output_part_ = output_part();
  send_part(last_output_part_, window_, verdict_accept);
  const Received verdict = receive_part(window_, iteration_, "the verdict on window " + std::to_string(window_));
  if (verdict.control.converged == verdict_stop)
    throw CouplingError(link_.partner_name() + " stopped the run: window " + std::to_string(window_) +
                        " did not converge in " + std::to_string(settings_.max_iterations) +
                        " coupling iterations (coupling.implicit.max_iterations)");
  if (verdict.control.converged == verdict_repeat) {
    repeat(verdict.part);
  } else {
    agree_on_window_end(last_window());
    accept(last_window() ? std::vector<double>{} : verdict.part, iteration_ + 1, true, -1, -1);
  }
}

std::vector<double> Participant::Impl::predicted(const std::vector<double>& last,
                                                 const std::vector<double>& previous) const {
  // Linear extrapolation of the converged outputs of the last two windows.
  std::vector<double> guess(last.size());
  for (std::size_t i = 0; i < guess.size(); ++i) guess[i] = 2 * last[i] - previous[i];
  return guess;
}

void Participant::Impl::complete_controller() {
  const bool parallel = settings_.implicit_mode == ImplicitMode::parallel;
  const bool last = last_window();
  // x̂: this program's output; in parallel mode followed by the partner's.
  std::vector<double> output = output_part();
  last_output_part_ = output;
  const std::size_t own_size = output.size();
  if (parallel) {
    const Received forces = receive_part(window_, iteration_, "forces of window " + std::to_string(window_));
    output.insert(output.end(), forces.part.begin(), forces.part.end());
  }
  // Residuals of the displacement and force fields, relative to the output.
  double largest_absolute = 0.0;  // for the message of a window that does not converge
  const auto field_residual = [&](std::size_t begin, std::size_t end, double& relative) {
    std::vector<double> r(end - begin);
    for (std::size_t i = begin; i < end; ++i) r[i - begin] = output[i] - sent_input_[i];
    const double r_norm = norm(link_.local(), r);
    const double x_norm = norm(link_.local(), std::span<const double>(output).subspan(begin, end - begin));
    relative = x_norm > 0 ? r_norm / x_norm : r_norm;
    largest_absolute = std::max(largest_absolute, r_norm);
    return r_norm <= std::max(settings_.absolute_tolerance, settings_.relative_tolerance * x_norm);
  };
  double residual_d = -1, residual_f = -1;
  bool converged = true;
  std::vector<double> weights;
  if (parallel) {
    converged = field_residual(0, own_size, residual_d);
    converged = field_residual(own_size, output.size(), residual_f) && converged;
    // Each field weighted by the inverse of its size, so that metres and
    // newtons count alike in the least-squares problem.
    const double d_scale = norm(link_.local(), std::span<const double>(output).first(own_size));
    const double f_scale = norm(link_.local(), std::span<const double>(output).subspan(own_size));
    weights.assign(output.size(), 1.0);
    for (std::size_t i = 0; i < output.size(); ++i) {
      const double scale = i < own_size ? d_scale : f_scale;
      weights[i] = scale > 0 ? 1.0 / scale : 1.0;
    }
  } else {
    converged = field_residual(0, own_size, side_ == Side::structure ? residual_d : residual_f);
  }
  const bool out_of_iterations = !converged && iteration_ + 1 >= settings_.max_iterations;
  if (out_of_iterations && settings_.stop_on_nonconvergence) {
    send_part(std::vector<double>(parallel ? own_size : output.size(), 0.0), window_, verdict_stop);
    throw CouplingError("window " + std::to_string(window_) + " (t = " + std::to_string(window_start_) + " to " +
                        std::to_string(window_start_ + window_length()) + " s) did not converge in " +
                        std::to_string(settings_.max_iterations) +
                        " coupling iterations (coupling.implicit.max_iterations); relative residual " +
                        std::to_string(std::max(residual_d, residual_f)) + ", absolute " +
                        exact_text(largest_absolute) + " (coupling.implicit.absolute_tolerance " +
                        exact_text(settings_.absolute_tolerance) + ")");
  }
  const bool accepted = converged || out_of_iterations;
  std::vector<double> next;
  if (accepted) {
    acceleration_->window_converged();
    previous_output_ = last_output_;
    last_output_ = output;
    next = predicted(last_output_, previous_output_);
  } else {
    next = acceleration_->next_input(sent_input_, output, weights);
  }
  // The follower's part of the next input goes to it with the verdict.
  const std::size_t follower_size = parallel ? own_size : next.size();
  send_part(std::vector<double>(next.begin(), next.begin() + static_cast<long>(follower_size)), window_,
            accepted ? verdict_accept : verdict_repeat);
  const int iterations = iteration_ + 1;
  if (accepted) agree_on_window_end(last);  // before the follower runs the next window (serial)
  std::vector<double> own_input;
  if (parallel) {
    own_input.assign(next.begin() + static_cast<long>(own_size), next.end());
  } else if (!(accepted && last) && !(accepted && stop_signal_ != 0)) {
    own_input = receive_part(accepted ? window_ + 1 : window_, accepted ? 0 : iteration_ + 1,
                             partner_data_name() + " of the next coupling iteration")
                    .part;
  }
  sent_input_ = std::move(next);
  if (accepted)
    accept(last ? std::vector<double>{} : own_input, iterations, converged, residual_d, residual_f);
  else
    repeat(own_input);
}

void Participant::Impl::accept(const std::vector<double>& next_input_part, int iterations, bool converged,
                               double residual_d, double residual_f) {
  WindowReport report;
  report.window = window_;
  report.start_time = window_start_;
  report.end_time = window_start_ + window_length();
  report.iterations = iterations;
  report.converged = converged;
  report.displacement_residual = residual_d;
  report.force_residual = residual_f;
  if (side_ == Side::structure) {
    report.impulse_given = component_sums(link_.local(), force_input_, window_length());
    report.impulse_applied = component_sums(link_.local(), ramp_.mean(), window_length());
  }
  reports_.push_back(report);
  if (side_ == Side::fluid && settings_.added_mass_operator) previous_wall_velocity_ = path_.velocity(window_length());

  window_start_ += window_length();
  elapsed_ = 0.0;
  ++window_;
  iteration_ = 0;
  if (side_ == Side::fluid) {
    path_.next_window();
    force_average_.reset();
  } else {
    ramp_.next_window();
    displacement_written_ = false;
  }
  // A restart continues from here: the next input is what the partner sends again.
  if (restart_agreed_) {
    capture_restart_state();
    next_restart_time_ = next_output_time(window_start_, restart_interval_);
    restart_point_due_ = true;
    restart_agreed_ = false;
  }
  if (stop_signal_ != 0) {
    stopped_ = true;
    exchange_->finish_sends("the partner to take the last interface data");
  } else if (!next_input_part.empty()) {
    aim(next_input_part);
  }
  window_completed_ = true;
  write_checkpoint_ = settings_.is_implicit() && is_ongoing() && !stopped_;
}

void Participant::Impl::repeat(const std::vector<double>& next_input_part) {
  elapsed_ = 0.0;
  ++iteration_;
  if (side_ == Side::fluid)
    force_average_.reset();
  else
    displacement_written_ = false;
  aim(next_input_part);
  window_completed_ = false;
  read_checkpoint_ = true;
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
