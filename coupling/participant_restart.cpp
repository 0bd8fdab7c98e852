// Participant: restart points (PROTOCOL.md, "Window ends"; participant_impl.hpp).
#include "coupling/participant_impl.hpp"

#include <algorithm>

#include "common/run/stop_signal.hpp"

namespace tankfsi::coupling {

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

}  // namespace tankfsi::coupling
